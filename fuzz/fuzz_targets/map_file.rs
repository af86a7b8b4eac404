//! The map file reader: any bytes give a map or an error naming the source, never a panic.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    if let Err(e) = mdp::Map::from_toml_bytes(data, "fuzz.toml") {
        assert!(e.to_string().contains("fuzz.toml"));
    }
});
