//! The wall clock runs are timed with. `std::time::Instant` panics on wasm32-unknown-unknown
//! (there is no OS clock); in a web page the same type comes from `web-time` (the page's
//! `performance.now()`).

#[cfg(not(target_arch = "wasm32"))]
pub use std::time::Instant;
#[cfg(target_arch = "wasm32")]
pub use web_time::Instant;
