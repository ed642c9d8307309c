//! Python values into the library's: a dict into the scene file's TOML table, keyword
//! arguments into the command line's overrides and a traced ray's request. Every error is a
//! `ValueError` naming the key (its path, in a scene dict).

use glam::DVec3;
use grinlight::commands::{Overrides, RayTrace, TraceControl};
use grinlight::curve::StepperKind;
use grinlight::settings::{unknown, Given, Key, DEFLECTION_TABLE};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyMapping, PyString, PyTuple};

/// A `ValueError` at `key` (none: the value as a whole).
fn bad(key: &str, message: impl std::fmt::Display) -> PyErr {
    match key {
        "" => PyValueError::new_err(message.to_string()),
        _ => PyValueError::new_err(format!("{key}: {message}")),
    }
}

/// How deep lists and dicts may nest in a scene dict: a scene file's are a few levels deep,
/// and a list or dict that holds itself would nest without end.
const MAX_NESTING: usize = 64;

/// The Python type name of `v`, for messages.
fn type_name(v: &Bound<'_, PyAny>) -> String {
    v.get_type()
        .name()
        .map_or_else(|_| "?".into(), |n| n.to_string())
}

/// A scene dict (any mapping with string keys) as the scene file's top-level table.
pub fn scene_table(data: &Bound<'_, PyAny>) -> PyResult<toml::Table> {
    let not_a_dict = || {
        PyValueError::new_err(format!(
            "a scene is a dict of the scene file's tables, got {}",
            type_name(data)
        ))
    };
    if data.cast::<PyMapping>().is_err() {
        return Err(not_a_dict());
    }
    match value(data, "", 0)? {
        toml::Value::Table(t) => Ok(t),
        _ => Err(not_a_dict()),
    }
}

/// One Python value at `path` as a TOML value: bool, int, float, str, a mapping with string
/// keys, a list or tuple; numpy arrays and scalars by their `tolist()`. None has no TOML
/// form (leave the key out). Nested more than [`MAX_NESTING`] deep (`depth` levels so far) is
/// an error — a list that holds itself among them.
fn value(v: &Bound<'_, PyAny>, path: &str, depth: usize) -> PyResult<toml::Value> {
    let at = |key: &str| match path {
        "" => key.to_string(),
        _ => format!("{path}.{key}"),
    };
    if depth > MAX_NESTING {
        let shown: String = path.chars().take(60).collect();
        return Err(bad(
            &shown,
            format!(
                "nested more than {MAX_NESTING} lists or dicts deep (a list or dict that holds \
                 itself?)"
            ),
        ));
    }
    Ok(if v.is_instance_of::<PyBool>() {
        toml::Value::Boolean(v.extract()?)
    } else if v.is_instance_of::<PyInt>() {
        toml::Value::Integer(
            v.extract()
                .map_err(|_| bad(path, format!("{v} is beyond a 64-bit integer")))?,
        )
    } else if v.is_instance_of::<PyFloat>() {
        toml::Value::Float(v.extract()?)
    } else if let Ok(s) = v.cast::<PyString>() {
        toml::Value::String(s.to_str()?.to_string())
    } else if let Ok(m) = v.cast::<PyMapping>() {
        let mut table = toml::Table::new();
        for item in m.items()?.iter() {
            let (k, x): (Bound<'_, PyAny>, Bound<'_, PyAny>) = item.extract()?;
            let key = k.cast::<PyString>().map_err(|_| {
                bad(
                    path,
                    format!("keys are strings, got {} ({})", k, type_name(&k)),
                )
            })?;
            let key = key.to_str()?.to_string();
            let converted = value(&x, &at(&key), depth + 1)?;
            table.insert(key, converted);
        }
        toml::Value::Table(table)
    } else if v.is_instance_of::<PyList>() || v.is_instance_of::<PyTuple>() {
        let mut items = Vec::new();
        for (i, x) in v.try_iter()?.enumerate() {
            items.push(value(&x?, &format!("{path}[{i}]"), depth + 1)?);
        }
        toml::Value::Array(items)
    } else if v.is_none() {
        return Err(bad(path, "None has no value in a scene: leave the key out"));
    } else if let Ok(list) = v.call_method0("tolist") {
        value(&list, path, depth + 1)?
    } else {
        return Err(bad(
            path,
            format!(
                "expected a number, string, bool, list or dict, got {}",
                type_name(v)
            ),
        ));
    })
}

/// A whole number ≥ 0 at `key`.
fn count<T: for<'a, 'py> FromPyObject<'a, 'py>>(v: &Bound<'_, PyAny>, key: &str) -> PyResult<T> {
    if v.is_instance_of::<PyBool>() || !v.is_instance_of::<PyInt>() {
        return Err(bad(
            key,
            format!("expected a whole number, got {v} ({})", type_name(v)),
        ));
    }
    v.extract()
        .map_err(|_| bad(key, format!("{v} is out of range (a whole number ≥ 0)")))
}

/// A finite number at `key`.
fn number(v: &Bound<'_, PyAny>, key: &str) -> PyResult<f64> {
    if v.is_instance_of::<PyBool>() {
        return Err(bad(key, "expected a number, got a bool"));
    }
    let x: f64 = v
        .extract()
        .map_err(|_| bad(key, format!("expected a number, got {}", type_name(v))))?;
    match x.is_finite() {
        true => Ok(x),
        false => Err(bad(key, format!("must be finite, got {x}"))),
    }
}

/// A Python value as a setting's value, before the settings table reads it (so a value is
/// refused in the scene file's words).
/// Integers are Python's and numpy's (whatever has `__index__`); numbers anything `float()`
/// reads.
fn given(v: &Bound<'_, PyAny>) -> Given {
    if let Ok(b) = v.cast::<PyBool>() {
        Given::Bool(b.is_true())
    } else if v.is_instance_of::<PyInt>() || v.hasattr("__index__").unwrap_or(false) {
        match v.extract::<i128>() {
            Ok(i) => Given::Integer(i),
            Err(_) => Given::Other(format!("{v} (out of range)")),
        }
    } else if let Ok(x) = v.extract::<f64>() {
        Given::Number(x)
    } else if let Ok(text) = v.extract::<String>() {
        Given::Text(text)
    } else {
        Given::Other(format!("a {}", type_name(v)))
    }
}

/// The settings given as keyword arguments (a value of None: not given), each replacing the
/// scene's `[render]`/`[camera]` key of its name ([`grinlight::settings::KEYS`]); `no_table`
/// is `deflection_table=False`.
pub fn overrides(d: &Bound<'_, PyDict>) -> PyResult<Overrides> {
    let mut o = Overrides::default();
    for (k, v) in d.iter() {
        let name: String = k.extract()?;
        if v.is_none() {
            continue;
        }
        if name == "no_table" {
            match given(&v) {
                Given::Bool(true) => o.set(&DEFLECTION_TABLE, false),
                Given::Bool(false) => {}
                other => return Err(bad(&name, format!("expected true or false, got {other}"))),
            }
            continue;
        }
        let Some(key) = Key::named(&name) else {
            return Err(bad(&name, unknown(&name, &["no_table"])));
        };
        o.set(key, given(&v));
    }
    Ok(o)
}

/// A point or direction: three finite numbers.
fn vector(v: &Bound<'_, PyAny>, key: &str) -> PyResult<DVec3> {
    let v = match v.call_method0("tolist") {
        Ok(list) => list,
        Err(_) => v.clone(),
    };
    let items: Vec<Bound<'_, PyAny>> = v
        .try_iter()
        .and_then(|it| it.collect())
        .map_err(|_| bad(key, "expected three numbers"))?;
    let [x, y, z] = items.as_slice() else {
        return Err(bad(
            key,
            format!("expected three numbers, got {}", items.len()),
        ));
    };
    Ok(DVec3::new(
        number(x, key)?,
        number(y, key)?,
        number(z, key)?,
    ))
}

/// The keyword arguments a trace takes besides the ray.
pub const TRACE_OPTIONS: [&str; 10] = [
    "stepper",
    "control",
    "tolerance",
    "step",
    "t_max",
    "t_min",
    "seed",
    "wavelength",
    "max_steps",
    "polarization",
];

/// A traced ray's request, as `grinlight trace`'s options give it (the same defaults).
pub fn ray_trace(
    medium: String,
    origin: &Bound<'_, PyAny>,
    direction: &Bound<'_, PyAny>,
    length: f64,
    options: &Bound<'_, PyDict>,
) -> PyResult<RayTrace> {
    let get = |key: &str| -> PyResult<Option<Bound<'_, PyAny>>> {
        Ok(options.get_item(key)?.filter(|v| !v.is_none()))
    };
    for k in options.keys() {
        let key: String = k.extract()?;
        if !TRACE_OPTIONS.contains(&key.as_str()) {
            return Err(bad(
                &key,
                format!("not a trace option (one of {})", TRACE_OPTIONS.join(", ")),
            ));
        }
    }
    let stepper: StepperKind = match get("stepper")? {
        None => RayTrace::STEPPER,
        Some(s) => {
            let name: String = s
                .extract()
                .map_err(|_| bad("stepper", "expected a stepper's name"))?;
            name.parse().map_err(|e| bad("stepper", e))?
        }
    };
    let opt_number =
        |key: &str| -> PyResult<Option<f64>> { get(key)?.map(|v| number(&v, key)).transpose() };
    let step = opt_number("step")?;
    let control = match get("control")?
        .map(|c| c.extract::<String>())
        .transpose()
        .map_err(|_| bad("control", "expected 'adaptive', 'fixed' or 'tessendorf'"))?
        .as_deref()
    {
        None | Some("adaptive") => TraceControl::Adaptive {
            tolerance: opt_number("tolerance")?,
        },
        Some("fixed") => TraceControl::Fixed { step },
        Some("tessendorf") => TraceControl::Tessendorf {
            step,
            t_max: opt_number("t_max")?.unwrap_or(1e-2),
            t_min: opt_number("t_min")?.unwrap_or(1e-4),
            seed: get("seed")?
                .map(|v| count(&v, "seed"))
                .transpose()?
                .unwrap_or(1),
        },
        Some(other) => {
            return Err(bad(
                "control",
                format!("unknown control '{other}' (adaptive, fixed, tessendorf)"),
            ))
        }
    };
    Ok(RayTrace {
        medium,
        from: vector(origin, "origin")?,
        dir: vector(direction, "direction")?,
        length: match length.is_finite() {
            true => length,
            false => return Err(bad("length", format!("must be finite, got {length}"))),
        },
        wavelength: opt_number("wavelength")?,
        stepper,
        control,
        max_steps: get("max_steps")?
            .map(|v| count(&v, "max_steps"))
            .transpose()?
            .unwrap_or(RayTrace::MAX_STEPS),
        polarization: get("polarization")?
            .map(|v| vector(&v, "polarization"))
            .transpose()?,
    })
}
