//! The C ABI (DESIGN.md layer 8, API.md).
