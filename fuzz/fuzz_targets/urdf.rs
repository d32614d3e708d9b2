#![no_main]
//! See `redundant_ik_fuzz::urdf`.
libfuzzer_sys::fuzz_target!(|data: &[u8]| redundant_ik_fuzz::urdf(data));
