//! Arbitrary bytes through the CSV reader (`ldh_fuzz::read_csv`).
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    ldh_fuzz::read_csv(data);
});
