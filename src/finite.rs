//! Nothing non-finite leaves `dlw` through its JSON: every `--json` document is checked before
//! it is printed, and a NaN or an infinity anywhere in it is an error that names where it sits
//! (its path, such as `closed_loop.sensed_vs_actual_rmse_deg`), with nothing printed.
//! `serde_json` writes such a number as `null`, which a reader cannot tell from "absent".
//!
//! The walk goes through `serde-value`, whose value keeps every `f64` as it is (`serde_json`'s
//! own `Value` has already turned NaN into `null`).

use serde::Serialize;
use serde_value::Value;

/// Why a document was not printed.
#[derive(Debug, thiserror::Error)]
pub enum NonFinite {
    /// A number in the document is NaN or infinite.
    #[error("the result holds {value} at {path}; nothing is printed (an input drove a computation out of range: check the values that feed {path})")]
    Number {
        /// Where, as dotted keys and `[i]` indices.
        path: String,
        /// The value, `NaN`, `inf` or `-inf`.
        value: String,
    },
    /// The document could not be serialized at all.
    #[error("serializing the result: {0}")]
    Serialize(String),
}

/// `value` as pretty JSON, or [`NonFinite`] if any number in it is NaN or infinite.
///
/// # Errors
/// [`NonFinite`].
pub fn to_json<T: Serialize + ?Sized>(value: &T) -> Result<String, NonFinite> {
    check(value)?;
    serde_json::to_string_pretty(value).map_err(|e| NonFinite::Serialize(e.to_string()))
}

/// Checks that every number of `value`, as it serializes, is finite.
///
/// # Errors
/// [`NonFinite::Number`] naming the first non-finite number's path.
pub fn check<T: Serialize + ?Sized>(value: &T) -> Result<(), NonFinite> {
    let tree = serde_value::to_value(value).map_err(|e| NonFinite::Serialize(e.to_string()))?;
    walk(&tree, &mut String::new())
}

fn walk(v: &Value, path: &mut String) -> Result<(), NonFinite> {
    let bad = |x: f64, path: &str| NonFinite::Number {
        path: if path.is_empty() {
            "the top".into()
        } else {
            path.to_owned()
        },
        value: format!("{x}"),
    };
    match v {
        Value::F64(x) if !x.is_finite() => Err(bad(*x, path)),
        Value::F32(x) if !x.is_finite() => Err(bad(f64::from(*x), path)),
        Value::Option(Some(inner)) | Value::Newtype(inner) => walk(inner, path),
        Value::Seq(items) => {
            for (i, item) in items.iter().enumerate() {
                let len = path.len();
                path.push_str(&format!("[{i}]"));
                walk(item, path)?;
                path.truncate(len);
            }
            Ok(())
        }
        Value::Map(entries) => {
            for (k, item) in entries {
                let len = path.len();
                let key = match k {
                    Value::String(s) => s.clone(),
                    other => format!("{other:?}"),
                };
                if !path.is_empty() {
                    path.push('.');
                }
                path.push_str(&key);
                walk(item, path)?;
                path.truncate(len);
            }
            Ok(())
        }
        _ => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Serialize)]
    struct Inner {
        rmse_deg: f64,
        maybe: Option<f64>,
    }

    #[derive(Serialize)]
    struct Outer {
        name: &'static str,
        runs: Vec<Inner>,
    }

    #[test]
    fn a_non_finite_number_is_named_by_its_path() {
        let ok = Outer {
            name: "x",
            runs: vec![Inner {
                rmse_deg: 1.0,
                maybe: None,
            }],
        };
        assert!(to_json(&ok).unwrap().contains("\"rmse_deg\": 1.0"));
        let bad = Outer {
            name: "x",
            runs: vec![
                Inner {
                    rmse_deg: 1.0,
                    maybe: None,
                },
                Inner {
                    rmse_deg: 2.0,
                    maybe: Some(f64::INFINITY),
                },
            ],
        };
        let e = to_json(&bad).unwrap_err().to_string();
        assert!(e.contains("runs[1].maybe") && e.contains("inf"), "{e}");
        let nan = Inner {
            rmse_deg: f64::NAN,
            maybe: None,
        };
        let e = to_json(&nan).unwrap_err().to_string();
        assert!(e.contains("NaN at rmse_deg"), "{e}");
    }
}
