//! `dlw discover --json` from the tests: run it, and read the names and gaps of its report.
#![allow(dead_code)]

use std::path::Path;

/// Runs `dlw discover --design DESIGN REC -o OUT --json`, asserts success, returns the JSON.
pub fn discover_json(design: &str, rec: &Path, out: &Path) -> serde_json::Value {
    try_discover_json(design, rec, out)
        .unwrap_or_else(|e| panic!("discover {} failed: {e}", rec.display()))
}

/// Runs `dlw discover --design DESIGN REC -o OUT --json`: the JSON, or the error it printed.
pub fn try_discover_json(
    design: &str,
    rec: &Path,
    out: &Path,
) -> Result<serde_json::Value, String> {
    let o = super::dlw(&[
        "discover".as_ref(),
        "--design".as_ref(),
        design.as_ref(),
        rec.as_os_str(),
        "-o".as_ref(),
        out.as_os_str(),
        "--json".as_ref(),
    ]);
    if o.status.success() {
        // `DLW_KEEP_JSON=DIR`: each report is also written to DIR, named by its recording, to
        // look at after a run.
        if let Ok(keep) = std::env::var("DLW_KEEP_JSON") {
            let name = rec
                .file_name()
                .map_or("report".into(), |n| n.to_string_lossy());
            let _ = std::fs::write(Path::new(&keep).join(format!("{name}.json")), &o.stdout);
        }
        Ok(serde_json::from_slice(&o.stdout).expect("discover --json prints JSON"))
    } else {
        Err(String::from_utf8_lossy(&o.stderr).trim().to_owned())
    }
}

/// The (effect, channel) pairs a report names, in its order.
pub fn named(report: &serde_json::Value) -> Vec<(String, String)> {
    report["discovered"]
        .as_array()
        .expect("a discovered array")
        .iter()
        .map(|d| {
            (
                d["effect"].as_str().unwrap().to_owned(),
                d["channel"].as_str().unwrap().to_owned(),
            )
        })
        .collect()
}

/// The effects an `ambiguous` entry of a report leaves open, in its order.
pub fn contenders(ambiguous: &serde_json::Value) -> Vec<String> {
    ambiguous["contenders"]
        .as_array()
        .expect("a contenders array")
        .iter()
        .map(|c| c[0].as_str().unwrap().to_owned())
        .collect()
}

/// Per channel, the held-out RMSE before and after.
pub fn gaps(report: &serde_json::Value) -> Vec<(String, f64, f64)> {
    report["gaps"]
        .as_array()
        .expect("a gaps array")
        .iter()
        .map(|g| {
            (
                g["channel"].as_str().unwrap().to_owned(),
                g["before"].as_f64().unwrap(),
                g["after"].as_f64().unwrap(),
            )
        })
        .collect()
}

/// The gap above the noise floor: `√(RMSE² − floor²)`, 0 below it.
pub fn above(rmse: f64, floor: f64) -> f64 {
    (rmse * rmse - floor * floor).max(0.0).sqrt()
}

/// What a recording holds, for judging what discovery said about it.
#[derive(Debug, Clone, PartialEq)]
pub enum Truth {
    /// Nothing: no name and no flag is right.
    Clean,
    /// A library effect on a channel: its name first is right.
    Library {
        /// The effect's name.
        effect: String,
        /// `plant`, `sensor1`, `sensor2`.
        channel: String,
    },
    /// A sensitivity that changes in a form outside the library: a flag on the channel, or
    /// `gain_drift` named there, is right.
    OutsideGain {
        /// The sensor.
        channel: String,
    },
}

/// What discovery said about one recording, against the truth.
#[derive(Debug, Clone, Default)]
pub struct Judgement {
    /// The right effect named first on the right channel (or, for an out-of-library gain,
    /// flagged or `gain_drift` there; for a clean recording, nothing).
    pub right: bool,
    /// Names or flags that must never be given, with why.
    pub wrong: Vec<String>,
    /// Something named or flagged on a clean recording.
    pub alarm: bool,
}

/// Judges `report` (`dlw discover --json`) against `truth`: a wrong name is any name other than
/// the truth's (on a clean recording, an alarm); `ambiguous` is allowed only on the truth's
/// channel with the true name among the contenders; a plant effect never names or flags a
/// sensor.
pub fn judge(report: &serde_json::Value, truth: &Truth) -> Judgement {
    let names = named(report);
    let flags: Vec<String> = report["unexplained"]
        .as_array()
        .unwrap()
        .iter()
        .map(|u| u["channel"].as_str().unwrap().to_owned())
        .collect();
    let ambiguous: Vec<(String, Vec<String>)> = report["ambiguous"]
        .as_array()
        .unwrap()
        .iter()
        .map(|a| (a["channel"].as_str().unwrap().to_owned(), contenders(a)))
        .collect();
    let mut j = Judgement::default();
    match truth {
        Truth::Clean => {
            j.alarm = !names.is_empty() || !flags.is_empty() || !ambiguous.is_empty();
            j.right = !j.alarm;
        }
        Truth::Library { effect, channel } => {
            let truth = (effect.clone(), channel.clone());
            j.right = names.first() == Some(&truth);
            for n in names.iter().filter(|n| **n != truth) {
                j.wrong.push(format!("named {} on {}", n.0, n.1));
            }
            for (ch, contenders) in &ambiguous {
                if ch != channel || !contenders.contains(effect) {
                    j.wrong
                        .push(format!("ambiguous on {ch} among {contenders:?}"));
                }
            }
            if channel == "plant" {
                for f in flags.iter().filter(|f| *f != "plant") {
                    j.wrong.push(format!("a plant effect flagged {f}"));
                }
            }
        }
        Truth::OutsideGain { channel } => {
            j.right = names.contains(&("gain_drift".to_owned(), channel.clone()))
                || flags.contains(channel);
            for n in names
                .iter()
                .filter(|n| !(n.0 == "gain_drift" && n.1 == *channel))
            {
                j.wrong.push(format!("named {} on {}", n.0, n.1));
            }
            for f in flags.iter().filter(|f| *f != channel) {
                j.wrong.push(format!("flagged {f}"));
            }
            for (ch, contenders) in &ambiguous {
                if ch != channel || !contenders.iter().any(|c| c == "gain_drift") {
                    j.wrong
                        .push(format!("ambiguous on {ch} among {contenders:?}"));
                }
            }
        }
    }
    j
}
