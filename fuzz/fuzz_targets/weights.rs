#![no_main]
//! See `redundant_ik_fuzz::weights`.
libfuzzer_sys::fuzz_target!(|data: &[u8]| redundant_ik_fuzz::weights(data));
