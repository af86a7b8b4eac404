//! From Python's arguments to a run's settings, by the path `csrl run` takes: the paper's
//! preset, then a settings file (here the text of one, or a file), then the arguments.

use std::path::PathBuf;

use csql::{RunSettings, SettingsDraft, StrategyKind, TrialCap};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};

use crate::{SettingsError, run_error};

/// The arguments of a run, as `csrl run` has them as flags.
pub(crate) struct RunArgs<'a> {
    /// `--world` (or `--map`).
    pub world: Option<String>,
    /// `--strategy`.
    pub strategy: Option<&'a str>,
    /// `--seed`.
    pub seed: Option<u64>,
    /// `--learner`.
    pub learner: Option<&'a str>,
    /// The settings: the text of a TOML file, or `@PATH` for the file itself, as
    /// `--config PATH` reads it.
    pub settings: Option<&'a str>,
    /// `--max-trials`.
    pub max_trials: Option<u32>,
    /// `--episodes`.
    pub episodes: Option<u32>,
    /// `--predict-sensing`.
    pub predict_sensing: Option<&'a str>,
}

fn bad(what: &str, value: &str, e: impl std::fmt::Display) -> PyErr {
    SettingsError::new_err(format!("{what} = {value:?}: {e}"))
}

impl RunArgs<'_> {
    /// The settings, as `csrl run` builds them from its flags (`crates/csrl/src/run.rs`).
    pub(crate) fn settings(&self) -> PyResult<RunSettings> {
        self.draft()?.build().map_err(|e| run_error(&e))
    }

    /// The settings given, then the arguments over them, not yet checked together.
    pub(crate) fn draft(&self) -> PyResult<SettingsDraft> {
        // The settings, then the arguments over them; everything is checked together
        // once all are in (`learner="u-tree"` gives the settings' `[u_tree]` its meaning).
        let mut draft = match self.settings {
            Some(text) => match text.strip_prefix('@') {
                Some(path) => SettingsDraft::from_file(&PathBuf::from(path)),
                None => SettingsDraft::from_toml(text, "settings"),
            }
            .map_err(|e| run_error(&e))?,
            None => SettingsDraft::default(),
        };
        draft.overlay(SettingsDraft {
            map: self.world.as_ref().map(Into::into),
            strategy: self
                .strategy
                .map(|k| k.parse::<StrategyKind>().map_err(|e| bad("strategy", k, e)))
                .transpose()?,
            seed: self.seed,
            max_trials: self
                .max_trials
                .map(|n| TrialCap::new(n).map_err(|e| run_error(&e)))
                .transpose()?,
            episodes: self
                .episodes
                .map(|n| TrialCap::new(n).map_err(|e| run_error(&e)))
                .transpose()?,
            predict_sensing: self
                .predict_sensing
                .map(|l| l.parse().map_err(|e| bad("predict_sensing", l, e)))
                .transpose()?,
            learner: self
                .learner
                .map(|l| l.parse().map_err(|e| bad("learner", l, e)))
                .transpose()?,
            ..SettingsDraft::default()
        });
        Ok(draft)
    }
}

/// How deep a settings mapping may nest (a table in a table, a list in a list): a
/// settings file has tables of values and no more, so this is far beyond any real one,
/// and low enough that walking it cannot exhaust the stack.
pub(crate) const MAX_SETTINGS_DEPTH: usize = 64;

/// How deep a value given to `dumps` may nest: serde_json's own limit when it reads, so
/// whatever `run_json` writes and `json.loads` reads back is written again.
pub(crate) const MAX_JSON_DEPTH: usize = 128;

/// The containers (lists, tuples, dicts) on the way from the top of a Python value to
/// the one being read: a container met again on its own way down contains itself.
struct Nesting {
    /// The addresses of the containers being read, outermost first.
    open: Vec<usize>,
    /// How deep the value may nest.
    limit: usize,
    /// What the errors call the value ("settings", "cannot write JSON").
    what: &'static str,
}

impl Nesting {
    fn new(limit: usize, what: &'static str) -> Self {
        Self {
            open: Vec::new(),
            limit,
            what,
        }
    }

    /// Enter the container `obj` (at `at`), refusing a cycle and a nesting past the limit.
    fn enter(&mut self, obj: &Bound<'_, PyAny>, at: &str) -> PyResult<()> {
        let id = obj.as_ptr() as usize;
        if self.open.contains(&id) {
            return Err(SettingsError::new_err(format!(
                "{}: {at} contains itself (a cycle of lists or dicts)",
                self.what
            )));
        }
        if self.open.len() >= self.limit {
            return Err(SettingsError::new_err(format!(
                "{}: {at} nests lists or dicts deeper than {} levels",
                self.what, self.limit
            )));
        }
        self.open.push(id);
        Ok(())
    }

    fn leave(&mut self) {
        self.open.pop();
    }
}

/// A Python mapping of settings (nested mappings for tables) as TOML text. A mapping
/// that contains itself, or nests deeper than [`MAX_SETTINGS_DEPTH`], is refused.
pub(crate) fn to_toml(obj: &Bound<'_, PyAny>) -> PyResult<String> {
    let mut nesting = Nesting::new(MAX_SETTINGS_DEPTH, "settings");
    let table = match to_value(obj, "settings", &mut nesting)? {
        toml::Value::Table(t) => t,
        _ => {
            return Err(SettingsError::new_err(
                "settings must be a mapping of names to values",
            ));
        }
    };
    toml::to_string(&table).map_err(|e| SettingsError::new_err(format!("settings: {e}")))
}

fn to_value(obj: &Bound<'_, PyAny>, at: &str, nesting: &mut Nesting) -> PyResult<toml::Value> {
    // bool before int: Python's True is an int too.
    if obj.is_instance_of::<PyBool>() {
        return Ok(toml::Value::Boolean(obj.extract()?));
    }
    if obj.is_instance_of::<PyInt>() {
        let v: i64 = obj.extract().map_err(|_| {
            SettingsError::new_err(format!("settings: {at} is an integer out of range"))
        })?;
        return Ok(toml::Value::Integer(v));
    }
    if obj.is_instance_of::<PyFloat>() {
        return Ok(toml::Value::Float(obj.extract()?));
    }
    if obj.is_instance_of::<PyString>() {
        return Ok(toml::Value::String(obj.extract()?));
    }
    if obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>() {
        nesting.enter(obj, at)?;
        let mut items = Vec::new();
        for (i, item) in obj.try_iter()?.enumerate() {
            items.push(to_value(&item?, &format!("{at}[{i}]"), nesting)?);
        }
        nesting.leave();
        return Ok(toml::Value::Array(items));
    }
    if let Ok(dict) = obj.cast::<PyDict>() {
        nesting.enter(obj, at)?;
        let mut table = toml::Table::new();
        for (k, v) in dict.iter() {
            let key: String = k.extract().map_err(|_| {
                SettingsError::new_err(format!("settings: a key of {at} is not a string"))
            })?;
            let here = if at == "settings" {
                key.clone()
            } else {
                format!("{at}.{key}")
            };
            table.insert(key, to_value(&v, &here, nesting)?);
        }
        nesting.leave();
        return Ok(toml::Value::Table(table));
    }
    let kind = obj
        .get_type()
        .name()
        .map_or_else(|_| "?".to_string(), |n| n.to_string());
    Err(SettingsError::new_err(format!(
        "settings: {at} is a {kind}; a setting is a bool, an int, a float, a str, a list or a dict"
    )))
}

/// Write a Python JSON value (None, bool, int, float, str, list, tuple, dict with str keys)
/// as serde_json writes the same value: compact, floats in their shortest form. A value
/// that contains itself, or nests deeper than [`MAX_JSON_DEPTH`], is refused.
pub(crate) fn write_json(obj: &Bound<'_, PyAny>, out: &mut String) -> PyResult<()> {
    write_json_in(
        obj,
        "the value",
        out,
        &mut Nesting::new(MAX_JSON_DEPTH, "cannot write JSON"),
    )
}

fn write_json_in(
    obj: &Bound<'_, PyAny>,
    at: &str,
    out: &mut String,
    nesting: &mut Nesting,
) -> PyResult<()> {
    let json = |e: serde_json::Error| SettingsError::new_err(format!("cannot write JSON: {e}"));
    if obj.is_none() {
        out.push_str("null");
    } else if obj.is_instance_of::<PyBool>() {
        out.push_str(if obj.extract::<bool>()? {
            "true"
        } else {
            "false"
        });
    } else if obj.is_instance_of::<PyInt>() {
        match obj.extract::<i64>() {
            Ok(v) => out.push_str(&v.to_string()),
            Err(_) => out.push_str(&obj.extract::<u64>()?.to_string()),
        }
    } else if obj.is_instance_of::<PyFloat>() {
        out.push_str(&serde_json::to_string(&obj.extract::<f64>()?).map_err(json)?);
    } else if obj.is_instance_of::<PyString>() {
        out.push_str(&serde_json::to_string(&obj.extract::<String>()?).map_err(json)?);
    } else if obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>() {
        nesting.enter(obj, at)?;
        out.push('[');
        for (i, item) in obj.try_iter()?.enumerate() {
            if i > 0 {
                out.push(',');
            }
            write_json_in(&item?, &format!("{at}[{i}]"), out, nesting)?;
        }
        out.push(']');
        nesting.leave();
    } else if let Ok(dict) = obj.cast::<PyDict>() {
        nesting.enter(obj, at)?;
        out.push('{');
        for (i, (k, v)) in dict.iter().enumerate() {
            if i > 0 {
                out.push(',');
            }
            let key: String = k
                .extract()
                .map_err(|_| SettingsError::new_err("cannot write JSON: a key is not a string"))?;
            out.push_str(&serde_json::to_string(&key).map_err(json)?);
            out.push(':');
            write_json_in(&v, &format!("{at}[{key:?}]"), out, nesting)?;
        }
        out.push('}');
        nesting.leave();
    } else {
        return Err(SettingsError::new_err(
            "cannot write JSON: a value is not None, a bool, an int, a float, a str, a list or a dict",
        ));
    }
    Ok(())
}
