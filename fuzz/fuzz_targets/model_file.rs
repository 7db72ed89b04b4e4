//! Arbitrary bytes as a model file (`ldh_core::fuzz_targets::model_file`).
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    ldh_core::fuzz_targets::model_file(data);
});
