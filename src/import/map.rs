//! `--tracker-map MAP.toml`: how to read a tracker log `dlw` does not know, as a small TOML
//! file (`docs/import.md`). Labs log the Aurora through their own programs (the Combined API
//! sample, modified), each with its own columns; the map names them:
//!
//! ```toml
//! header_line = 5                     # 1-based line of the column names
//! time = [["Hour", "h"], ["Minutes", "min"], ["Seconds", "s"], ["ms", "ms"]]
//! frame = "Sample:"                   # optional frame counter
//! [[tool]]                            # --tool N picks the N-th
//! quaternion = ["qoa", "qxa", "qya", "qza"]    # w, x, y, z
//! position_mm = ["Xa", "Ya", "Za"]             # optional
//! missing = "all-zero"                # or "empty"
//! ```
//!
//! NDI's own layout (NDI Track, the Combined API sample) is one built-in map, [`TrackerMap::ndi`]:
//! `Frame#` as the frame, `timespec_s` + `timespec_ns` as the time when both are there, one tool
//! per `Q0` column with `Q0, Qx, Qy, Qz`, missing when empty.
//!
//! **Names.** Header names match after trimming spaces, case ignored. A name the header holds
//! several times (NDI writes `Frame#`, `Q0`, `Qx`, … once per tool) is taken in order: the
//! `n`-th `[[tool]]` naming it takes its `n`-th occurrence, and `frame` and `time` take the
//! occurrence of the tool picked by `--tool` (its own frame counter).

use serde::Deserialize;

/// Why a map could not be used.
#[derive(Debug, thiserror::Error)]
pub enum MapError {
    /// Not valid TOML for a map.
    #[error("tracker map: {0}")]
    Parse(String),
    /// A value out of range.
    #[error("tracker map: {key} = {value} {limit}")]
    Value {
        /// The key.
        key: String,
        /// The value given.
        value: String,
        /// What it must be.
        limit: &'static str,
    },
}

/// A unit of a time column: the seconds one count of it is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TimeUnit {
    /// Hours.
    Hour,
    /// Minutes.
    Minute,
    /// Seconds.
    Second,
    /// Milliseconds.
    Milli,
    /// Microseconds.
    Micro,
    /// Nanoseconds.
    Nano,
}

impl TimeUnit {
    /// The units a map may name, as written.
    pub const NAMES: [&'static str; 6] = ["h", "min", "s", "ms", "us", "ns"];

    /// The unit written `name`.
    pub fn from_name(name: &str) -> Option<Self> {
        Some(match name {
            "h" => TimeUnit::Hour,
            "min" => TimeUnit::Minute,
            "s" => TimeUnit::Second,
            "ms" => TimeUnit::Milli,
            "us" => TimeUnit::Micro,
            "ns" => TimeUnit::Nano,
            _ => return None,
        })
    }

    /// Seconds per count.
    pub fn seconds(self) -> f64 {
        match self {
            TimeUnit::Hour => 3600.0,
            TimeUnit::Minute => 60.0,
            TimeUnit::Second => 1.0,
            TimeUnit::Milli => 1e-3,
            TimeUnit::Micro => 1e-6,
            TimeUnit::Nano => 1e-9,
        }
    }
}

/// How a lost tool is written.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Missing {
    /// Every field of the tool (quaternion and position) is 0.
    AllZero,
    /// The quaternion's fields are empty (NDI: `Missing,,,,,,,,`).
    Empty,
}

/// One tool's columns.
#[derive(Debug, Clone, PartialEq)]
pub struct ToolColumns {
    /// `w, x, y, z` (scalar first).
    pub quaternion: [String; 4],
    /// `x, y, z` (mm), when the map names them.
    pub position_mm: Option<[String; 3]>,
    /// How the log writes the tool lost.
    pub missing: Missing,
}

/// A tracker log's layout.
#[derive(Debug, Clone, PartialEq)]
pub struct TrackerMap {
    /// The 1-based line of the column names (lines before it are skipped: a logger's
    /// preamble).
    pub header_line: usize,
    /// The time: seconds are the sum of each column times its unit. Empty: the log has no time
    /// columns (then `frame` is the clock).
    pub time: Vec<(String, TimeUnit)>,
    /// The tracker's frame counter, when the log has one: then the clock is the frame counter
    /// over the frame rate.
    pub frame: Option<String>,
    /// The tools, in the order `--tool N` counts them.
    pub tools: Vec<ToolColumns>,
}

/// The map as written in TOML.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct MapFile {
    header_line: usize,
    #[serde(default)]
    time: Vec<(String, String)>,
    #[serde(default)]
    frame: Option<String>,
    #[serde(default)]
    tool: Vec<ToolFile>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ToolFile {
    quaternion: [String; 4],
    #[serde(default)]
    position_mm: Option<[String; 3]>,
    missing: Missing,
}

/// The most lines a map may skip before its header.
pub const MAX_HEADER_LINE: usize = 10_000;

impl TrackerMap {
    /// Parses and checks a map.
    ///
    /// # Errors
    /// [`MapError`] naming the key and the value.
    pub fn from_toml(text: &str) -> Result<Self, MapError> {
        let file: MapFile =
            toml::from_str(text).map_err(|e| MapError::Parse(crate::limits::parser_message(&e)))?;
        let bad = |key: &str, value: String, limit| MapError::Value {
            key: key.to_owned(),
            value,
            limit,
        };
        if !(1..=MAX_HEADER_LINE).contains(&file.header_line) {
            return Err(bad(
                "header_line",
                file.header_line.to_string(),
                "must be a line number from 1 to 10000",
            ));
        }
        let mut time = Vec::with_capacity(file.time.len());
        for (column, unit) in file.time {
            let u = TimeUnit::from_name(&unit).ok_or_else(|| {
                bad(
                    "time",
                    format!("[{column:?}, {unit:?}]"),
                    "has a unit that is not one of h, min, s, ms, us, ns",
                )
            })?;
            time.push((column, u));
        }
        if time.is_empty() && file.frame.is_none() {
            return Err(bad(
                "time",
                "[]".into(),
                "must name at least one column when there is no frame counter",
            ));
        }
        if file.tool.is_empty() {
            return Err(bad(
                "tool",
                "[]".into(),
                "must list at least one [[tool]] with its quaternion columns",
            ));
        }
        let tools = file
            .tool
            .into_iter()
            .map(|t| ToolColumns {
                quaternion: t.quaternion,
                position_mm: t.position_mm,
                missing: t.missing,
            })
            .collect();
        Ok(Self {
            header_line: file.header_line,
            time,
            frame: file.frame,
            tools,
        })
    }

    /// NDI's own layout, as NDI Track and the Combined API sample write it, for a log whose
    /// header (at `header_line`) is `header`: `Frame#` is the frame counter, `timespec_s` and
    /// `timespec_ns` the time when both are there, and each `Q0` starts a tool whose quaternion
    /// is `Q0, Qx, Qy, Qz` (empty when `Missing`). `None` when the header has no `Frame#` or
    /// no `Q0`: not NDI's layout.
    pub fn ndi(header_line: usize, header: &[&str]) -> Option<Self> {
        let has = |name: &str| header.iter().any(|h| h.eq_ignore_ascii_case(name));
        let tools = header
            .iter()
            .filter(|h| h.eq_ignore_ascii_case("Q0"))
            .count();
        if !has("Frame#") || tools == 0 {
            return None;
        }
        let time = if has("timespec_s") && has("timespec_ns") {
            vec![
                ("timespec_s".to_owned(), TimeUnit::Second),
                ("timespec_ns".to_owned(), TimeUnit::Nano),
            ]
        } else {
            Vec::new()
        };
        let tool = ToolColumns {
            quaternion: ["Q0", "Qx", "Qy", "Qz"].map(str::to_owned),
            position_mm: None,
            missing: Missing::Empty,
        };
        Some(Self {
            header_line,
            time,
            frame: Some("Frame#".to_owned()),
            tools: vec![tool; tools],
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_issue_map_reads_and_bad_maps_name_the_key() {
        let text = r#"
header_line = 5
time = [["Hour", "h"], ["Minutes", "min"], ["Seconds", "s"], ["ms", "ms"]]
frame = "Sample:"
[[tool]]
quaternion = ["qoa", "qxa", "qya", "qza"]
position_mm = ["Xa", "Ya", "Za"]
missing = "all-zero"
[[tool]]
quaternion = ["qob", "qxb", "qyb", "qzb"]
missing = "empty"
"#;
        let map = TrackerMap::from_toml(text).unwrap();
        assert_eq!(map.header_line, 5);
        assert_eq!(map.time[0], ("Hour".to_owned(), TimeUnit::Hour));
        assert_eq!(map.time[3].1.seconds(), 1e-3);
        assert_eq!(map.tools.len(), 2);
        assert_eq!(map.tools[1].missing, Missing::Empty);
        for (bad, says) in [
            (text.replace("\"ms\"]]", "\"jiffies\"]]"), "jiffies"),
            (text.replace("header_line = 5", "header_line = 0"), "header_line = 0"),
            (text.replace("missing = \"empty\"", "missing = \"nan\""), "missing"),
            (text.replace("frame =", "frames ="), "frames"),
            ("header_line = 1\ntime = [[\"t\", \"s\"]]\n".to_owned(), "tool"),
            (
                "header_line = 1\n[[tool]]\nquaternion = [\"a\",\"b\",\"c\",\"d\"]\nmissing = \"empty\"\n"
                    .to_owned(),
                "time",
            ),
        ] {
            let err = TrackerMap::from_toml(&bad).unwrap_err().to_string();
            assert!(err.contains(says), "{says}: {err}");
        }
    }

    #[test]
    fn ndi_layout_is_one_built_in_map() {
        let header: Vec<&str> =
            "#Tools,ToolInfo,Frame#,PortHandle,Face#,timespec_s,timespec_ns,TransformStatus,Q0,Qx,Qy,Qz,Tx,Ty,Tz,Error,#Markers,ToolInfo,Frame#,PortHandle,Face#,timespec_s,timespec_ns,TransformStatus,Q0,Qx,Qy,Qz,Tx,Ty,Tz,Error,#Markers"
                .split(',')
                .collect();
        let map = TrackerMap::ndi(1, &header).unwrap();
        assert_eq!(map.tools.len(), 2);
        assert_eq!(map.frame.as_deref(), Some("Frame#"));
        assert_eq!(map.time.len(), 2);
        assert!(TrackerMap::ndi(1, &["Sample:", "qoa"]).is_none());
    }
}
