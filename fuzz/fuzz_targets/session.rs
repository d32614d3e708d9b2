#![no_main]
//! See `redundant_ik_fuzz::session`.
libfuzzer_sys::fuzz_target!(|data: &[u8]| redundant_ik_fuzz::session(data));
