//! `cargo xtask cube`: CUBE, the synthetic data set of the costly-feature literature,
//! generated from its published recipe and a seed.
//!
//! Each object has 20 features and one of 8 classes. Three fair bits `b0, b1, b2` give the
//! class `c = b0 + 2 b1 + 4 b2`; features `c`, `c + 1` and `c + 2` (counted from 0) hold
//! the bits plus normal noise of standard deviation `sigma`, and every other feature is
//! uniform on [0, 1]. So which features tell the class depends on the class: an object's
//! first tests must find where its three informative features are. The recipe is Shim,
//! Hwang and Yang's (NeurIPS 2018, after Rückstieß, Osendorfer and van der Smagt 2011),
//! whose experiments use `sigma` = 0.3.

use std::fmt::Write as _;
use std::path::PathBuf;

use anyhow::{Context, Result, bail};
use rand::{RngExt, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;

/// The features of CUBE.
pub const FEATURES: usize = 20;

/// `cargo xtask cube`'s arguments.
#[derive(clap::Args, Debug)]
pub struct CubeArgs {
    /// Objects to generate.
    #[arg(long, default_value_t = 10_000)]
    pub objects: usize,
    /// The standard deviation of the noise on the informative features.
    #[arg(long, default_value_t = 0.3)]
    pub sigma: f64,
    /// The seed of the generator (Xoshiro256++).
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// The CSV file to write (a header line, then one line per object).
    #[arg(long, default_value = "data/uci/cube/cube.csv")]
    pub out: PathBuf,
}

/// CUBE as CSV text: a header (`f0` to `f19`, `class`), then one line per object, every
/// value with 4 decimals.
pub fn cube_csv(objects: usize, sigma: f64, seed: u64) -> String {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let mut text = String::new();
    for f in 0..FEATURES {
        let _ = write!(text, "f{f},");
    }
    text.push_str("class\n");
    let mut row = [0.0_f64; FEATURES];
    for _ in 0..objects {
        let bits: [u32; 3] = std::array::from_fn(|_| u32::from(rng.random_bool(0.5)));
        let class = bits[0] + 2 * bits[1] + 4 * bits[2];
        for value in row.iter_mut() {
            *value = rng.random::<f64>();
        }
        for (j, &bit) in bits.iter().enumerate() {
            row[class as usize + j] = f64::from(bit) + sigma * normal(&mut rng);
        }
        for value in &row {
            let _ = write!(text, "{value:.4},");
        }
        let _ = writeln!(text, "{class}");
    }
    text
}

/// A standard normal draw (Box and Muller), from two uniform draws.
fn normal(rng: &mut Xoshiro256PlusPlus) -> f64 {
    // 1 - u is in (0, 1]: its logarithm is finite.
    let u = 1.0 - rng.random::<f64>();
    let v = rng.random::<f64>();
    (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
}

/// Write CUBE to `args.out`.
pub fn cube(args: &CubeArgs) -> Result<()> {
    if args.objects == 0 || args.objects > 10_000_000 {
        bail!("--objects {}: from 1 to 10,000,000", args.objects);
    }
    if !(args.sigma.is_finite() && args.sigma >= 0.0) {
        bail!(
            "--sigma {}: a finite standard deviation, 0 or more",
            args.sigma
        );
    }
    let text = cube_csv(args.objects, args.sigma, args.seed);
    if let Some(parent) = args.out.parent().filter(|p| !p.as_os_str().is_empty()) {
        std::fs::create_dir_all(parent)
            .with_context(|| format!("creating {}", parent.display()))?;
    }
    std::fs::write(&args.out, text).with_context(|| format!("writing {}", args.out.display()))?;
    crate::emit(&format!(
        "wrote {} ({} objects, sigma {}, seed {})\n",
        args.out.display(),
        args.objects,
        args.sigma,
        args.seed
    ))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The committed file is what the recipe and its seed give, byte for byte.
    #[test]
    fn the_committed_cube_is_regenerated_from_its_seed() {
        let path =
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/uci/cube/cube.csv");
        let committed = std::fs::read_to_string(path).unwrap();
        assert_eq!(committed, cube_csv(10_000, 0.3, 1));
    }

    /// Each class's three informative features hold its bits (up to the noise), in the
    /// class's place; the classes come in about equal shares.
    #[test]
    fn the_informative_features_hold_the_class_bits() {
        let text = cube_csv(4000, 0.0, 7);
        let mut counts = [0usize; 8];
        for line in text.lines().skip(1) {
            let cells: Vec<f64> = line.split(',').map(|c| c.parse().unwrap()).collect();
            let class = cells[FEATURES] as usize;
            counts[class] += 1;
            for j in 0..3 {
                assert_eq!(
                    cells[class + j],
                    f64::from((class >> j) as u32 & 1),
                    "{line}"
                );
            }
            assert!(cells[..FEATURES].iter().all(|v| (0.0..=1.0).contains(v)));
        }
        assert!(
            counts.iter().all(|&n| (400..600).contains(&n)),
            "{counts:?}"
        );
        assert_ne!(cube_csv(10, 0.3, 1), cube_csv(10, 0.3, 2));
    }
}
