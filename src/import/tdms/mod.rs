//! NI's TDMS files, read against NI's published description of the format ("TDMS File Format
//! Internal Structure"): a file is a sequence of segments, each a 28-byte lead-in, optional
//! metadata and optional raw data.
//!
//! - **Lead-in:** the tag `TDSm`, the table of contents (always little-endian: `kTocMetaData`
//!   1<<1, `kTocNewObjList` 1<<2, `kTocRawData` 1<<3, `kTocInterleavedData` 1<<5,
//!   `kTocBigEndian` 1<<6, `kTocDAQmxRawData` 1<<7), the version (4712 or 4713), the offset of
//!   the next segment and of the raw data, both counted from the end of the lead-in. A next
//!   segment offset of all ones means the writer never closed the segment: it runs to the end
//!   of the file.
//! - **Metadata:** objects (`/`, `/'Group'`, `/'Group'/'Channel'`), each with a raw data index
//!   (`0xFFFFFFFF` none, `0x00000000` the same as in the last segment, `0x69120000` and
//!   `0x69130000` DAQmx raw data, refused here, otherwise: data type, dimension 1, number of
//!   values, and for text the bytes) and properties. Without `kTocNewObjList` the segment's
//!   objects are the last segment's with the new ones appended; without `kTocMetaData` the
//!   last segment's objects and indexes hold as they were.
//! - **Raw data:** one chunk is every object's values in list order (non-interleaved) or value
//!   by value across the objects (interleaved); the raw data repeats chunks up to the next
//!   segment.
//!
//! Numbers are decoded as `f64` (i8 to u64, f32, f64, booleans, timestamps as seconds since
//! 1904-01-01 UTC); a linear scale in the channel's (or its group's, or the file's) properties
//! (`NI_Number_Of_Scales`, `NI_Scale[n]_Scale_Type = "Linear"`, `NI_Scale[n]_Linear_Slope`,
//! `NI_Scale[n]_Linear_Y_Intercept`, `NI_Scale[n]_Linear_Input_Source`) is applied unless
//! `NI_Scaling_Status` says `scaled`; other scale types are refused, naming them. Every length
//! read from the file is checked against the bytes that are there before anything is
//! allocated for it.

use std::collections::HashMap;

mod daq;
mod scale;
mod segment;

pub use daq::daq_table;
use scale::linear_scales;
use segment::{
    decode_run, decode_text_run, type_name, DataType, LeadIn, ObjectList, RawIndex, Run,
    TOC_META_DATA, TOC_RAW_DATA,
};

/// 2⁶⁴, the denominator of a timestamp's fraction of a second.
const TWO_POW_64: f64 = 18_446_744_073_709_551_616.0;
/// The advice given for DAQmx raw data.
const DAQMX_ADVICE: &str = "export scaled data instead: open the file in LabVIEW, DIAdem or \
    NI's TDMS viewer and save the channels as scaled (double) values, or read it with Python's \
    npTDMS (which applies DAQmx's scalers) and write a CSV for --daq-format csv";

/// Why a TDMS file could not be read.
#[derive(Debug, thiserror::Error)]
pub enum TdmsError {
    /// The file is empty.
    #[error("the TDMS file is empty")]
    Empty,
    /// The lead-in's tag is not `TDSm`.
    #[error("byte {offset}: segment {segment} starts with {found:?}, not the TDMS tag \"TDSm\" (is this a TDMS file?)")]
    NotTdms {
        /// The segment (0-based).
        segment: usize,
        /// Its byte offset.
        offset: usize,
        /// The four bytes found.
        found: String,
    },
    /// An index file was given.
    #[error(
        "this is a TDMS index file (tag \"TDSh\", a .tdms_index); give the .tdms file it indexes"
    )]
    IndexFile,
    /// A version NI has not published.
    #[error("segment {segment} at byte {offset}: TDMS version {version} (known: 4712, 4713)")]
    Version {
        /// The segment.
        segment: usize,
        /// Its byte offset.
        offset: usize,
        /// The version found.
        version: u32,
    },
    /// A segment runs past the end of the file.
    #[error("segment {segment} at byte {offset} runs to byte {end}, but the file has {file_bytes} bytes: the file is truncated mid-segment (copied while it was being written?)")]
    Truncated {
        /// The segment.
        segment: usize,
        /// Its byte offset.
        offset: usize,
        /// Where it says it ends.
        end: u64,
        /// The file's length.
        file_bytes: usize,
    },
    /// Metadata that cannot be read.
    #[error("segment {segment} at byte {offset}: {reason}")]
    Metadata {
        /// The segment.
        segment: usize,
        /// The byte where reading failed.
        offset: usize,
        /// Why.
        reason: String,
    },
    /// DAQmx raw data.
    #[error("{what} holds DAQmx raw data (as DAQmx's own TDMS logging writes it), which dlw does not decode; {DAQMX_ADVICE}")]
    DaqmxRaw {
        /// The object or segment.
        what: String,
    },
    /// A channel asked for is not in the file.
    #[error("the TDMS file has no channel {channel:?} (its channels: {found})")]
    NoChannel {
        /// The name asked for.
        channel: String,
        /// Its channels, `Group/Channel`.
        found: String,
    },
    /// A bare channel name found in several groups.
    #[error("channel {channel:?} is in several groups ({found}); name it as Group/Channel")]
    Ambiguous {
        /// The name asked for.
        channel: String,
        /// The candidates.
        found: String,
    },
    /// A channel whose values are not numbers.
    #[error("channel {channel:?} holds {kind}, not numbers")]
    NotNumeric {
        /// The channel.
        channel: String,
        /// What it holds.
        kind: &'static str,
    },
    /// A value that is not finite.
    #[error("channel {channel:?} value {index} is {value}, not a finite number")]
    NotFinite {
        /// The channel.
        channel: String,
        /// The 0-based sample.
        index: usize,
        /// The value.
        value: f64,
    },
    /// A scale that cannot be applied.
    #[error("channel {channel:?}: {reason}")]
    Scaling {
        /// The channel.
        channel: String,
        /// Why.
        reason: String,
    },
    /// Channels of different lengths.
    #[error("channel {first:?} has {first_len} values but {other:?} has {other_len}; the channels of one import must be sampled together")]
    Lengths {
        /// The first channel.
        first: String,
        /// Its length.
        first_len: usize,
        /// The other.
        other: String,
        /// Its length.
        other_len: usize,
    },
    /// Channels on different clocks.
    #[error("channel {first:?} has wf_increment {first_s} s but {other:?} has {other_s} s; the channels of one import must be sampled together")]
    Increments {
        /// The first channel.
        first: String,
        /// Its increment (s).
        first_s: f64,
        /// The other.
        other: String,
        /// Its increment (s).
        other_s: f64,
    },
    /// No channel was asked for.
    #[error("no TDMS channel was asked for")]
    NothingAsked,
    /// No time base.
    #[error("the TDMS channels have no wf_increment (waveform timing), no time channel (time_s, time, Time or t) was found, and no --time-column or --daq-rate-hz was given")]
    NoTime,
    /// A bad `wf_increment` or rate.
    #[error("{what} {value} is not a sample interval or rate (finite and above 0)")]
    Rate {
        /// Which value.
        what: String,
        /// The value.
        value: f64,
    },
    /// A time channel that does not increase.
    #[error(
        "time channel {channel:?}: sample {index} at {time_s} s does not come after {previous_s} s"
    )]
    Time {
        /// The channel.
        channel: String,
        /// The 0-based sample.
        index: usize,
        /// Its time (s).
        time_s: f64,
        /// The previous sample's (s).
        previous_s: f64,
    },
    /// Fewer samples than an import needs.
    #[error("the TDMS channels have {rows} samples; an import needs at least {min}")]
    TooShort {
        /// Samples read.
        rows: usize,
        /// Needed.
        min: usize,
    },
}

/// A timestamp: seconds since 1904-01-01 00:00 UTC and a fraction in units of 2⁻⁶⁴ s.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Timestamp {
    /// Whole seconds since 1904-01-01 00:00 UTC.
    pub seconds: i64,
    /// The fraction of a second, in 2⁻⁶⁴ s.
    pub fraction: u64,
}

impl Timestamp {
    /// Seconds since 1904-01-01 00:00 UTC (about 0.5 µs resolution today).
    pub fn as_seconds(&self) -> f64 {
        self.seconds as f64 + self.fraction as f64 / TWO_POW_64
    }
}

/// A property's value.
#[derive(Debug, Clone, PartialEq)]
pub enum Property {
    /// A signed integer.
    Int(i64),
    /// An unsigned integer.
    UInt(u64),
    /// A float.
    Float(f64),
    /// A boolean.
    Bool(bool),
    /// Text.
    Text(String),
    /// A timestamp.
    Time(Timestamp),
    /// A type dlw reads past but does not use (extended float, complex).
    Other,
}

impl Property {
    /// The value as a number, where it is one.
    pub fn as_f64(&self) -> Option<f64> {
        match self {
            Property::Int(v) => Some(*v as f64),
            Property::UInt(v) => Some(*v as f64),
            Property::Float(v) => Some(*v),
            Property::Bool(v) => Some(f64::from(u8::from(*v))),
            _ => None,
        }
    }
}

/// A channel's waveform properties.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Waveform {
    /// `wf_start_time`: when the first sample was taken.
    pub start_time: Option<Timestamp>,
    /// `wf_increment`: the sample interval (s).
    pub increment_s: Option<f64>,
    /// `wf_samples`: the samples of one write (not the channel's length).
    pub samples_per_write: Option<u64>,
}

/// One object of the file: its path, its properties (later segments' replacing earlier ones'),
/// where its values are.
#[derive(Debug, Clone, Default)]
struct Object {
    path: Vec<String>,
    properties: Vec<(String, Property)>,
    runs: Vec<Run>,
    /// The last raw data index given, for `INDEX_SAME`.
    last_index: Option<RawIndex>,
}

impl Object {
    fn property(&self, name: &str) -> Option<&Property> {
        self.properties
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, v)| v)
    }

    fn set_property(&mut self, name: String, value: Property) {
        match self.properties.iter_mut().find(|(n, _)| *n == name) {
            Some(slot) => slot.1 = value,
            None => self.properties.push((name, value)),
        }
    }
}

/// A channel of a [`TdmsFile`], as [`TdmsFile::find`] names it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ChannelId(usize);

/// A TDMS file's structure, read over its bytes; values are decoded when asked for.
#[derive(Debug)]
pub struct TdmsFile<'a> {
    bytes: &'a [u8],
    objects: Vec<Object>,
    by_path: HashMap<String, usize>,
}

impl<'a> TdmsFile<'a> {
    /// Reads the structure of the TDMS file `bytes`.
    ///
    /// # Errors
    /// [`TdmsError`]: not TDMS, a segment past the end of the file, metadata that cannot be
    /// read, DAQmx raw data.
    pub fn parse(bytes: &'a [u8]) -> Result<Self, TdmsError> {
        if bytes.is_empty() {
            return Err(TdmsError::Empty);
        }
        let mut file = TdmsFile {
            bytes,
            objects: Vec::new(),
            by_path: HashMap::new(),
        };
        let mut list = ObjectList::new();
        let (mut offset, mut segment) = (0, 0);
        while offset < bytes.len() {
            let lead = LeadIn::read(bytes, offset, segment)?;
            if lead.toc & TOC_META_DATA != 0 {
                file.read_metadata(&lead, &mut list)?;
            }
            if lead.toc & TOC_RAW_DATA != 0 {
                file.place_raw_data(&lead, &list)?;
            }
            offset = lead.end;
            segment += 1;
        }
        Ok(file)
    }

    /// Every channel, as `Group/Channel`, in the order the file first lists them.
    pub fn channel_names(&self) -> Vec<String> {
        self.objects
            .iter()
            .filter(|o| o.path.len() == 2)
            .map(|o| o.path.join("/"))
            .collect()
    }

    /// The channel named `Group/Channel`, or just `Channel` when no other group has one so
    /// named.
    ///
    /// # Errors
    /// [`TdmsError::NoChannel`] listing the channels there are; [`TdmsError::Ambiguous`].
    pub fn find(&self, name: &str) -> Result<ChannelId, TdmsError> {
        let channels = || {
            self.objects
                .iter()
                .enumerate()
                .filter(|(_, o)| o.path.len() == 2)
        };
        let full: Vec<usize> = channels()
            .filter(|(_, o)| o.path.join("/") == name)
            .map(|(i, _)| i)
            .collect();
        let bare: Vec<usize> = channels()
            .filter(|(_, o)| o.path[1] == name)
            .map(|(i, _)| i)
            .collect();
        let found = if full.len() == 1 { full } else { bare };
        match found.as_slice() {
            [one] => Ok(ChannelId(*one)),
            [] => Err(TdmsError::NoChannel {
                channel: name.to_owned(),
                found: self.channel_names().join(", "),
            }),
            many => Err(TdmsError::Ambiguous {
                channel: name.to_owned(),
                found: many
                    .iter()
                    .map(|&i| self.objects[i].path.join("/"))
                    .collect::<Vec<_>>()
                    .join(", "),
            }),
        }
    }

    /// The channel's name, `Group/Channel`.
    pub fn name(&self, id: ChannelId) -> String {
        self.objects[id.0].path.join("/")
    }

    /// The channel's properties, in the order first written, later values replacing earlier.
    pub fn properties(&self, id: ChannelId) -> &[(String, Property)] {
        &self.objects[id.0].properties
    }

    /// The channel's waveform properties.
    pub fn waveform(&self, id: ChannelId) -> Waveform {
        let o = &self.objects[id.0];
        Waveform {
            start_time: match o.property("wf_start_time") {
                Some(Property::Time(t)) => Some(*t),
                _ => None,
            },
            increment_s: o.property("wf_increment").and_then(Property::as_f64),
            samples_per_write: o
                .property("wf_samples")
                .and_then(Property::as_f64)
                .filter(|v| *v >= 0.0)
                .map(|v| v as u64),
        }
    }

    /// The channel's data type, as npTDMS names it (`DoubleFloat`, `Int16`, `String`, …);
    /// `None` for a channel that never had raw data.
    pub fn type_name(&self, id: ChannelId) -> Option<&'static str> {
        let o = &self.objects[id.0];
        o.runs
            .first()
            .map(|r| r.code)
            .or(o.last_index.map(|r| r.code))
            .map(type_name)
    }

    /// How many values the channel has across every segment.
    pub fn length(&self, id: ChannelId) -> usize {
        self.objects[id.0]
            .runs
            .iter()
            .map(|r| r.chunks * r.count)
            .sum()
    }

    /// Whether the channel holds text.
    pub fn is_text(&self, id: ChannelId) -> bool {
        self.objects[id.0]
            .runs
            .iter()
            .any(|r| r.dtype == DataType::Text)
    }

    /// The channel's strings across every segment (empty for a channel that is not text).
    pub fn texts(&self, id: ChannelId) -> Vec<String> {
        let mut out = Vec::new();
        for run in &self.objects[id.0].runs {
            if run.dtype == DataType::Text {
                decode_text_run(self.bytes, run, &mut out);
            }
        }
        out
    }

    /// The channel's values across every segment as written: no scale applied, not checked
    /// to be finite (text and opaque types read as NaN).
    pub fn raw_values(&self, id: ChannelId) -> Vec<f64> {
        let mut values = Vec::new();
        for run in &self.objects[id.0].runs {
            if run.dtype != DataType::Text {
                decode_run(self.bytes, run, &mut values);
            }
        }
        values
    }

    /// The channel's values across every segment, scaled by its linear scales.
    ///
    /// # Errors
    /// [`TdmsError::NotNumeric`] for text and other types; [`TdmsError::Scaling`] for a scale
    /// that is not linear or is malformed; [`TdmsError::NotFinite`].
    pub fn values(&self, id: ChannelId) -> Result<Vec<f64>, TdmsError> {
        let o = &self.objects[id.0];
        let name = self.name(id);
        let mut values = Vec::new();
        for run in &o.runs {
            match run.dtype {
                DataType::Text => {
                    return Err(TdmsError::NotNumeric {
                        channel: name,
                        kind: "text",
                    })
                }
                DataType::Opaque(_) => {
                    return Err(TdmsError::NotNumeric {
                        channel: name,
                        kind: "extended-precision or complex numbers",
                    })
                }
                _ => decode_run(self.bytes, run, &mut values),
            }
        }
        let chain = self.scale_chain(o).map_err(|reason| TdmsError::Scaling {
            channel: name.clone(),
            reason,
        })?;
        for v in values.iter_mut() {
            *v = chain
                .iter()
                .fold(*v, |x, (slope, intercept)| x * slope + intercept);
        }
        if let Some(index) = values.iter().position(|v| !v.is_finite()) {
            return Err(TdmsError::NotFinite {
                channel: name,
                index,
                value: values[index],
            });
        }
        Ok(values)
    }

    /// The linear scales to apply to the raw values, first to last, as (slope, intercept):
    /// from the channel's properties, else its group's, else the file's.
    fn scale_chain(&self, channel: &Object) -> Result<Vec<(f64, f64)>, String> {
        let group = self.by_path.get(&path_key(&channel.path[..1]));
        let root = self.by_path.get(&path_key(&[]));
        for holder in [
            Some(channel),
            group.map(|&i| &self.objects[i]),
            root.map(|&i| &self.objects[i]),
        ]
        .into_iter()
        .flatten()
        {
            if let Some(chain) = linear_scales(holder)? {
                return Ok(chain);
            }
        }
        Ok(Vec::new())
    }
}

/// A lookup key for an object path (components joined by a character TDMS names cannot hold
/// unescaped).
fn path_key(path: &[String]) -> String {
    path.join("\u{0}")
}

#[cfg(test)]
mod tests {
    use super::segment::{
        parse_path, INDEX_DAQMX_FORMAT, INDEX_NONE, INDEX_SAME, TOC_BIG_ENDIAN, TOC_INTERLEAVED,
        TOC_NEW_OBJ_LIST,
    };
    use super::*;

    /// A little-endian segment: lead-in with `toc`, metadata `meta`, raw data `raw`.
    fn segment(toc: u32, meta: &[u8], raw: &[u8]) -> Vec<u8> {
        let mut s = b"TDSm".to_vec();
        s.extend(toc.to_le_bytes());
        s.extend(4713u32.to_le_bytes());
        s.extend(((meta.len() + raw.len()) as u64).to_le_bytes());
        s.extend((meta.len() as u64).to_le_bytes());
        s.extend(meta);
        s.extend(raw);
        s
    }

    fn string(s: &str) -> Vec<u8> {
        let mut b = (s.len() as u32).to_le_bytes().to_vec();
        b.extend(s.as_bytes());
        b
    }

    /// A test property: a float or text.
    #[derive(Clone, Copy)]
    enum P<'s> {
        F(f64),
        T(&'s str),
    }

    /// A test object: its path, its raw data (type code, values) or none, its properties.
    type TestObject<'s> = (&'s str, Option<(u32, u64)>, &'s [(&'s str, P<'s>)]);

    /// Metadata listing `objects` as (path, Some((type code, values)) or None, properties);
    /// type code 0 writes "same as before".
    fn meta(objects: &[TestObject<'_>]) -> Vec<u8> {
        let mut m = (objects.len() as u32).to_le_bytes().to_vec();
        for (path, raw, props) in objects {
            m.extend(string(path));
            match raw {
                None => m.extend(INDEX_NONE.to_le_bytes()),
                Some((0, _)) => m.extend(INDEX_SAME.to_le_bytes()),
                Some((code, n)) => {
                    m.extend(20u32.to_le_bytes());
                    m.extend(code.to_le_bytes());
                    m.extend(1u32.to_le_bytes());
                    m.extend(n.to_le_bytes());
                }
            }
            m.extend((props.len() as u32).to_le_bytes());
            for (name, value) in *props {
                m.extend(string(name));
                match value {
                    P::F(v) => {
                        m.extend(10u32.to_le_bytes());
                        m.extend(v.to_le_bytes());
                    }
                    P::T(t) => {
                        m.extend(0x20u32.to_le_bytes());
                        m.extend(string(t));
                    }
                }
            }
        }
        m
    }

    const ALL: u32 = TOC_META_DATA | TOC_RAW_DATA | TOC_NEW_OBJ_LIST;

    #[test]
    fn paths_parse_with_escaped_quotes() {
        assert_eq!(parse_path("/"), Some(vec![]));
        assert_eq!(
            parse_path("/'G'/'it''s'"),
            Some(vec!["G".to_owned(), "it's".to_owned()])
        );
        assert_eq!(parse_path("/G"), None);
        assert_eq!(parse_path("/'a"), None);
        assert_eq!(parse_path("/'a'/'b'/'c'"), None);
    }

    /// Segments without metadata reuse the last ones' layout; "same as before" keeps an
    /// object's index; interleaved i16 with a linear scale; big-endian f64.
    #[test]
    fn segments_reuse_metadata_and_interleave() {
        let mut file = Vec::new();
        let m = meta(&[
            ("/", None, &[]),
            ("/'g'", None, &[]),
            ("/'g'/'a'", Some((10, 2)), &[("wf_increment", P::F(0.5))]),
            ("/'g'/'b'", Some((10, 2)), &[]),
        ]);
        let raw: Vec<u8> = [1.0f64, 2.0, 10.0, 20.0]
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        file.extend(segment(ALL, &m, &raw));
        // No metadata: the same two channels, two chunks.
        let raw2: Vec<u8> = [3.0f64, 4.0, 30.0, 40.0, 5.0, 6.0, 50.0, 60.0]
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        file.extend(segment(TOC_RAW_DATA, &[], &raw2));
        // Metadata with "same as before" for a, interleaved.
        let m3 = meta(&[
            ("/'g'/'a'", Some((0, 0)), &[]),
            ("/'g'/'b'", Some((10, 2)), &[]),
        ]);
        let raw3: Vec<u8> = [7.0f64, 70.0, 8.0, 80.0]
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        file.extend(segment(
            TOC_META_DATA | TOC_RAW_DATA | TOC_INTERLEAVED,
            &m3,
            &raw3,
        ));
        let f = TdmsFile::parse(&file).unwrap();
        let a = f.find("a").unwrap();
        assert_eq!(
            f.values(a).unwrap(),
            [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0]
        );
        assert_eq!(
            f.values(f.find("g/b").unwrap()).unwrap(),
            [10.0, 20.0, 30.0, 40.0, 50.0, 60.0, 70.0, 80.0]
        );
        assert_eq!(f.waveform(a).increment_s, Some(0.5));
    }

    #[test]
    fn scaled_i16_and_big_endian() {
        let m = meta(&[(
            "/'g'/'s'",
            Some((2, 3)),
            &[
                ("NI_Number_Of_Scales", P::F(2.0)),
                ("NI_Scale[1]_Scale_Type", P::T("Linear")),
                ("NI_Scale[1]_Linear_Slope", P::F(0.5)),
                ("NI_Scale[1]_Linear_Y_Intercept", P::F(1.0)),
                ("NI_Scale[1]_Linear_Input_Source", P::F(0.0)),
                ("NI_Scale[0]_Scale_Type", P::T("Linear")),
                ("NI_Scale[0]_Linear_Slope", P::F(2.0)),
                ("NI_Scale[0]_Linear_Y_Intercept", P::F(-1.0)),
            ],
        )]);
        let raw: Vec<u8> = [100i16, -2, 0]
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        let file = segment(ALL, &m, &raw);
        let f = TdmsFile::parse(&file).unwrap();
        // Scale 0 first (2x - 1), then scale 1 (0.5y + 1).
        let want: Vec<f64> = [100.0f64, -2.0, 0.0]
            .iter()
            .map(|x| 0.5 * (2.0 * x - 1.0) + 1.0)
            .collect();
        assert_eq!(f.values(f.find("s").unwrap()).unwrap(), want);

        // Big-endian: the ToC stays little-endian, everything else is big.
        let mut be = b"TDSm".to_vec();
        be.extend((ALL | TOC_BIG_ENDIAN).to_le_bytes());
        let mut meta_be = 1u32.to_be_bytes().to_vec();
        meta_be.extend(8u32.to_be_bytes());
        meta_be.extend(b"/'g'/'x'");
        meta_be.extend(20u32.to_be_bytes());
        meta_be.extend(10u32.to_be_bytes());
        meta_be.extend(1u32.to_be_bytes());
        meta_be.extend(2u64.to_be_bytes());
        meta_be.extend(0u32.to_be_bytes());
        let raw_be: Vec<u8> = [1.5f64, -2.5]
            .iter()
            .flat_map(|v| v.to_be_bytes())
            .collect();
        be.extend(4713u32.to_be_bytes());
        be.extend(((meta_be.len() + raw_be.len()) as u64).to_be_bytes());
        be.extend((meta_be.len() as u64).to_be_bytes());
        be.extend(meta_be);
        be.extend(raw_be);
        let f = TdmsFile::parse(&be).unwrap();
        assert_eq!(f.values(f.find("x").unwrap()).unwrap(), [1.5, -2.5]);
    }

    /// A segment its writer never closed (next segment offset all ones) runs to the end of the
    /// file; a last chunk cut short gives each channel the values whole in it.
    #[test]
    fn an_unclosed_segment_runs_to_the_end_of_the_file() {
        let m = meta(&[
            ("/'g'/'a'", Some((10, 2)), &[]),
            ("/'g'/'b'", Some((10, 2)), &[]),
        ]);
        // Two whole chunks, then a third with a's two values and half of b's first.
        let values = [1.0f64, 2.0, 10.0, 20.0, 3.0, 4.0, 30.0, 40.0, 5.0, 6.0];
        let mut raw: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
        raw.extend([0u8; 4]);
        let mut file = segment(ALL, &m, &raw);
        file[12..20].copy_from_slice(&u64::MAX.to_le_bytes());
        let f = TdmsFile::parse(&file).unwrap();
        assert_eq!(
            f.values(f.find("a").unwrap()).unwrap(),
            [1.0, 2.0, 3.0, 4.0, 5.0, 6.0]
        );
        assert_eq!(
            f.values(f.find("b").unwrap()).unwrap(),
            [10.0, 20.0, 30.0, 40.0]
        );
    }

    /// Garbage, truncation and huge counts are errors, never panics or huge allocations.
    #[test]
    fn bad_files_are_errors() {
        let m = meta(&[("/'g'/'a'", Some((10, 4)), &[])]);
        let raw: Vec<u8> = [1.0f64, 2.0, 3.0, 4.0]
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        let good = segment(ALL, &m, &raw);
        for cut in [1, 10, 27, 28, 40, good.len() - 1] {
            let err = TdmsFile::parse(&good[..cut]).unwrap_err();
            assert!(
                matches!(err, TdmsError::Truncated { .. }),
                "cut at {cut}: {err}"
            );
        }
        // A short file that is not TDMS is called that, not truncated.
        let err = TdmsFile::parse(b"x").unwrap_err();
        assert!(matches!(err, TdmsError::NotTdms { .. }), "{err}");
        // A value count far beyond the segment.
        let huge = meta(&[("/'g'/'a'", Some((10, u64::MAX / 2)), &[])]);
        let err = TdmsFile::parse(&segment(ALL, &huge, &raw)).unwrap_err();
        assert!(err.to_string().contains("more raw data"), "{err}");
        // A string length beyond the metadata.
        let mut bad = m.clone();
        bad[4..8].copy_from_slice(&u32::MAX.to_le_bytes());
        let err = TdmsFile::parse(&segment(ALL, &bad, &raw)).unwrap_err();
        assert!(err.to_string().contains("needs 4294967295 bytes"), "{err}");
        // DAQmx raw data.
        let mut daqmx = m.clone();
        let at = 4 + 4 + "/'g'/'a'".len();
        daqmx[at..at + 4].copy_from_slice(&INDEX_DAQMX_FORMAT.to_le_bytes());
        let err = TdmsFile::parse(&segment(ALL, &daqmx, &raw)).unwrap_err();
        assert!(err.to_string().contains("DAQmx raw data"), "{err}");
        // Random bytes after a valid tag.
        let mut rng = 0x1234_5678_9abc_def0u64;
        for _ in 0..2000 {
            let mut junk = good.clone();
            for _ in 0..4 {
                rng ^= rng << 13;
                rng ^= rng >> 7;
                rng ^= rng << 17;
                let i = 8 + (rng as usize) % (junk.len() - 8);
                junk[i] = (rng >> 32) as u8;
            }
            if let Ok(f) = TdmsFile::parse(&junk) {
                for name in f.channel_names() {
                    let _ = f.find(&name).and_then(|id| f.values(id));
                }
            }
        }
        // An unknown channel lists the ones there are.
        let f = TdmsFile::parse(&good).unwrap();
        let err = f.find("nope").unwrap_err().to_string();
        assert!(err.contains("nope") && err.contains("g/a"), "{err}");
    }
}
