//! Arbitrary bytes through the CSV reader (`ldh_core::fuzz_targets::read_csv`).
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    ldh_core::fuzz_targets::read_csv(data);
});
