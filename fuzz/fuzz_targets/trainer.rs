#![no_main]
//! See `redundant_ik_fuzz::trainer`.
libfuzzer_sys::fuzz_target!(|data: &[u8]| redundant_ik_fuzz::trainer(data));
