//! Every use here must be refused by the workspace's clippy.toml.

/// The global generator.
pub fn global() -> u64 {
    use rand::RngExt;
    rand::rng().random()
}

/// A generator whose stream may change between rand versions.
pub fn non_portable(rng: &mut rand::rngs::StdRng) -> u64 {
    use rand::RngExt;
    rng.random()
}
