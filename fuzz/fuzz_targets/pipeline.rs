//! A recording decoded from arbitrary bytes through the per-recording pipeline
//! (`ldh_fuzz::pipeline`).
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    ldh_fuzz::pipeline(data);
});
