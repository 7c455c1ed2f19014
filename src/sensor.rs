//! Which sensor: the one typed identity every analysis, config and report uses.
//!
//! A joint carries one sensor, or two in opposite planes (BSN joints, Eq. 7). Sensor 1 sits in
//! the plane `+y_s` and is stretched by a positive angle; sensor 2 sits in `−y_s`. Names in
//! files and JSON are `sensor1` and `sensor2`; on the command line `1`, `2` or `both`.

use std::fmt;
use std::str::FromStr;

use dlw_estimator::SensorPlane;
use serde::{Deserialize, Serialize};

/// One of a joint's sensors.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub enum Sensor {
    /// Sensor 1, in the plane `+y_s` (the recording's `v1_V`).
    #[serde(rename = "sensor1")]
    One,
    /// Sensor 2, in the plane `−y_s` (the recording's `v2_V`).
    #[serde(rename = "sensor2")]
    Two,
}

impl Sensor {
    /// Both sensors, in order.
    pub const ALL: [Sensor; 2] = [Sensor::One, Sensor::Two];

    /// 1 or 2, as the paper and the recording's columns number them.
    pub fn number(self) -> usize {
        match self {
            Sensor::One => 1,
            Sensor::Two => 2,
        }
    }

    /// 0 or 1: the position in per-sensor arrays.
    pub fn index(self) -> usize {
        self.number() - 1
    }

    /// The sensor numbered `n` (1 or 2).
    pub fn from_number(n: usize) -> Option<Sensor> {
        match n {
            1 => Some(Sensor::One),
            2 => Some(Sensor::Two),
            _ => None,
        }
    }

    /// `sensor1` or `sensor2`: the name in files, JSON and channel lists.
    pub fn key(self) -> &'static str {
        match self {
            Sensor::One => "sensor1",
            Sensor::Two => "sensor2",
        }
    }

    /// The sensor that reads `plane`: sensor 1 on `+y_s`, sensor 2 on `−y_s`.
    pub fn on_plane(plane: SensorPlane) -> Sensor {
        match plane {
            SensorPlane::PlusYs => Sensor::One,
            SensorPlane::MinusYs => Sensor::Two,
        }
    }

    /// The plane the sensor sits in, as the estimator config states it.
    pub fn plane(self) -> SensorPlane {
        match self {
            Sensor::One => SensorPlane::PlusYs,
            Sensor::Two => SensorPlane::MinusYs,
        }
    }
}

impl fmt::Display for Sensor {
    /// `sensor 1` or `sensor 2`, for sentences.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "sensor {}", self.number())
    }
}

/// Which sensors an estimate or a fit uses: one of them, or both together (Eq. 7).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(into = "String", try_from = "String")]
pub enum Sensors {
    /// One sensor alone.
    Single(Sensor),
    /// Both sensors, combined by their difference (Eq. 7).
    Both,
}

impl Sensors {
    /// The sensors used, in order.
    pub fn members(self) -> &'static [Sensor] {
        match self {
            Sensors::Single(Sensor::One) => &[Sensor::One],
            Sensors::Single(Sensor::Two) => &[Sensor::Two],
            Sensors::Both => &Sensor::ALL,
        }
    }

    /// `sensor1`, `sensor2` or `both`: the name in files and JSON.
    pub fn key(self) -> &'static str {
        match self {
            Sensors::Single(s) => s.key(),
            Sensors::Both => "both",
        }
    }
}

impl fmt::Display for Sensors {
    /// `sensor 1`, `sensor 2` or `both sensors`, for sentences.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Sensors::Single(s) => s.fmt(f),
            Sensors::Both => f.write_str("both sensors"),
        }
    }
}

/// A sensor name that is none of `1`, `2`, `both`, `sensor1`, `sensor2`.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown sensor {0:?}: expected 1, 2 or both")]
pub struct UnknownSensor(pub String);

impl FromStr for Sensors {
    type Err = UnknownSensor;

    /// `1`/`sensor1`, `2`/`sensor2` or `both` (the command line's and the files' names).
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim() {
            "1" | "sensor1" => Ok(Sensors::Single(Sensor::One)),
            "2" | "sensor2" => Ok(Sensors::Single(Sensor::Two)),
            "both" => Ok(Sensors::Both),
            other => Err(UnknownSensor(other.chars().take(40).collect())),
        }
    }
}

impl FromStr for Sensor {
    type Err = UnknownSensor;

    /// `1`/`sensor1` or `2`/`sensor2`.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.parse::<Sensors>()? {
            Sensors::Single(sensor) => Ok(sensor),
            Sensors::Both => Err(UnknownSensor(s.to_owned())),
        }
    }
}

impl From<Sensors> for String {
    fn from(s: Sensors) -> String {
        s.key().to_owned()
    }
}

impl TryFrom<String> for Sensors {
    type Error = UnknownSensor;
    fn try_from(s: String) -> Result<Self, Self::Error> {
        s.parse()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_through_text_and_json() {
        for s in [
            Sensors::Single(Sensor::One),
            Sensors::Single(Sensor::Two),
            Sensors::Both,
        ] {
            assert_eq!(s.key().parse::<Sensors>().unwrap(), s);
            let json = serde_json::to_string(&s).unwrap();
            assert_eq!(serde_json::from_str::<Sensors>(&json).unwrap(), s);
        }
        assert_eq!(serde_json::to_string(&Sensor::Two).unwrap(), "\"sensor2\"");
        assert_eq!("1".parse::<Sensor>().unwrap(), Sensor::One);
        assert!("both".parse::<Sensor>().is_err());
        assert!("3".parse::<Sensors>().is_err());
    }

    #[test]
    fn sensor_one_is_the_plus_plane() {
        assert_eq!(Sensor::One.plane().sign(), 1.0);
        assert_eq!(Sensor::Two.plane().sign(), -1.0);
        assert_eq!(Sensors::Both.members(), &[Sensor::One, Sensor::Two]);
    }
}
