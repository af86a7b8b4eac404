//! Parameters read from files: valid values accepted, invalid ones refused at parse
//! time with an error that names the parameter, unknown keys refused.

use qlearn::{Discount, Epsilon, Error, LearningRate, MoveCap, Params, Start, Temperature};

fn parse(text: &str) -> Result<Params, String> {
    toml::from_str::<Params>(text).map_err(|e| e.to_string())
}

const PAPER: &str = "learning_rate = 1.0\ndiscount = 0.9\ntemperature = 0.4\nmax_moves = 100\n";

#[test]
fn the_paper_preset_round_trips_through_toml_and_json() {
    assert_eq!(parse(PAPER).unwrap(), Params::tan1991());
    let text = toml::to_string(&Params::tan1991()).unwrap();
    assert_eq!(parse(&text).unwrap(), Params::tan1991());
    let json = serde_json::to_string(&Params::tan1991()).unwrap();
    assert_eq!(
        serde_json::from_str::<Params>(&json).unwrap(),
        Params::tan1991()
    );
    // The paper's symbols are accepted as aliases.
    let greek = "beta = 1.0\ngamma = 0.9\ntemperature = 0.4\nmax_moves = 100\n";
    assert_eq!(parse(greek).unwrap(), Params::tan1991());
}

#[test]
fn invalid_values_are_refused_and_named() {
    for (key, bad, name) in [
        ("learning_rate = 1.0", "learning_rate = 0.0", "beta"),
        ("learning_rate = 1.0", "learning_rate = 1.5", "beta"),
        ("discount = 0.9", "discount = 1.0", "gamma"),
        ("discount = 0.9", "discount = -0.5", "gamma"),
        ("temperature = 0.4", "temperature = 0.0", "temperature"),
        ("temperature = 0.4", "temperature = -1.0", "temperature"),
        ("temperature = 0.4", "temperature = nan", "temperature"),
        ("temperature = 0.4", "temperature = inf", "temperature"),
        ("max_moves = 100", "max_moves = 0", "max_moves"),
    ] {
        let text = PAPER.replace(key, bad);
        let err = parse(&text).unwrap_err();
        assert!(err.contains(name), "{bad}: {err}");
    }
    let err = parse(&format!("{PAPER}epsilon = 0.1\n")).unwrap_err();
    assert!(err.contains("epsilon"), "{err}");
    assert!(parse("learning_rate = 1.0\n").is_err());
}

#[test]
fn constructors_check_the_boundaries() {
    assert!(LearningRate::new(f64::MIN_POSITIVE).is_ok());
    assert_eq!(
        LearningRate::new(-0.0),
        Err(Error::LearningRate { value: -0.0 })
    );
    assert!(Discount::new(0.0).is_ok());
    assert!(Discount::new(1.0 - f64::EPSILON).is_ok());
    assert!(Temperature::new(1e-6).is_ok());
    assert!(Temperature::new(f64::NAN).is_err());
    assert!(Epsilon::new(1.0).is_ok());
    assert!(Epsilon::new(-f64::EPSILON).is_err());
    assert_eq!(MoveCap::new(1).unwrap().get(), 1);
    assert_eq!(MoveCap::new(0), Err(Error::MoveCap { value: 0 }));
    assert_eq!(
        serde_json::from_str::<Epsilon>("2.0")
            .unwrap_err()
            .to_string(),
        "exploration rate (epsilon) must be in [0, 1], got 2"
    );
}

#[test]
fn starts_read_from_toml() {
    #[derive(serde::Deserialize)]
    struct S {
        start: Start,
    }
    let s: S = toml::from_str("start = \"uniform\"").unwrap();
    assert_eq!(s.start, Start::Uniform);
    let s: S = toml::from_str("start = { fixed = 4 }").unwrap();
    assert_eq!(s.start, Start::Fixed(mdp::StateId(4)));
    assert!(toml::from_str::<S>("start = \"anywhere\"").is_err());
}
