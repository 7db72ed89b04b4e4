//! Arbitrary bytes as a model file (`ldh_fuzz::model_file`).
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    ldh_fuzz::model_file(data);
});
