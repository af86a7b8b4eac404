//! Run settings from TOML: any text is applied or refused, never a panic; accepted settings
//! are valid.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        let mut s = csql::RunSettings::tan1991("tan3x3", csql::StrategyKind::Lazy, 1);
        if s.apply_toml(text, "fuzz.toml").is_ok() {
            assert!(s.validate().is_ok());
        }
    }
});
