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

use super::daq_csv::{DaqTable, MIN_ROWS, TIME_NAMES};

/// A data file's lead-in tag.
const TAG_DATA: &[u8; 4] = b"TDSm";
/// An index file's (`.tdms_index`) lead-in tag.
const TAG_INDEX: &[u8; 4] = b"TDSh";
/// The lead-in's length (bytes).
const LEAD_IN_BYTES: usize = 28;
/// `kTocMetaData`: the segment has metadata.
const TOC_META_DATA: u32 = 1 << 1;
/// `kTocNewObjList`: the segment's object list replaces the last one.
const TOC_NEW_OBJ_LIST: u32 = 1 << 2;
/// `kTocRawData`: the segment has raw data.
const TOC_RAW_DATA: u32 = 1 << 3;
/// `kTocInterleavedData`: the raw data is interleaved.
const TOC_INTERLEAVED: u32 = 1 << 5;
/// `kTocBigEndian`: the segment's numbers (not the table of contents) are big-endian.
const TOC_BIG_ENDIAN: u32 = 1 << 6;
/// `kTocDAQmxRawData`: the segment holds DAQmx raw data.
const TOC_DAQMX_RAW: u32 = 1 << 7;
/// The format versions NI has published.
const VERSIONS: [u32; 2] = [4712, 4713];
/// Raw data index: the same as the object's in the last segment.
const INDEX_SAME: u32 = 0x0000_0000;
/// Raw data index: no raw data in this segment.
const INDEX_NONE: u32 = 0xFFFF_FFFF;
/// Raw data index: DAQmx format changing scaler.
const INDEX_DAQMX_FORMAT: u32 = 0x6912_0000;
/// Raw data index: DAQmx digital line scaler.
const INDEX_DAQMX_DIGITAL: u32 = 0x6913_0000;
/// Data type code of DAQmx raw data.
const TYPE_DAQMX: u32 = 0xFFFF_FFFF;
/// Next segment offset of a segment its writer never closed.
const SEGMENT_UNCLOSED: u64 = u64::MAX;
/// Scale input source meaning the raw data.
const SOURCE_RAW: u64 = 0xFFFF_FFFF;
/// 2⁶⁴, the denominator of a timestamp's fraction of a second.
const TWO_POW_64: f64 = 18_446_744_073_709_551_616.0;
/// How channels' `wf_increment` may differ, relatively, and still be one clock.
const INCREMENT_TOLERANCE: f64 = 1e-9;

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

/// A raw data type.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum DataType {
    I8,
    I16,
    I32,
    I64,
    U8,
    U16,
    U32,
    U64,
    F32,
    F64,
    Bool,
    Timestamp,
    Text,
    /// Read past, not decoded (extended float, complex): its size in bytes.
    Opaque(usize),
}

impl DataType {
    fn from_code(code: u32) -> Option<Self> {
        Some(match code {
            1 => DataType::I8,
            2 => DataType::I16,
            3 => DataType::I32,
            4 => DataType::I64,
            5 => DataType::U8,
            6 => DataType::U16,
            7 => DataType::U32,
            8 => DataType::U64,
            9 | 0x19 => DataType::F32,
            10 | 0x1A => DataType::F64,
            11 | 0x1B => DataType::Opaque(16),
            0x20 => DataType::Text,
            0x21 => DataType::Bool,
            0x44 => DataType::Timestamp,
            0x0008_000C => DataType::Opaque(8),
            0x0010_000D => DataType::Opaque(16),
            _ => return None,
        })
    }

    /// Bytes per value; `None` for text, whose size is given per segment.
    fn size(self) -> Option<usize> {
        Some(match self {
            DataType::I8 | DataType::U8 | DataType::Bool => 1,
            DataType::I16 | DataType::U16 => 2,
            DataType::I32 | DataType::U32 | DataType::F32 => 4,
            DataType::I64 | DataType::U64 | DataType::F64 => 8,
            DataType::Timestamp => 16,
            DataType::Opaque(n) => n,
            DataType::Text => return None,
        })
    }
}

/// An object's raw data index in one segment.
#[derive(Debug, Clone, Copy, PartialEq)]
struct RawIndex {
    dtype: DataType,
    values: u64,
    /// For text: the bytes of the segment's strings and their offsets.
    text_bytes: u64,
}

impl RawIndex {
    /// Bytes per chunk, checked against `limit` (the segment's raw data).
    fn bytes(&self, limit: usize) -> Option<usize> {
        let b = match self.dtype.size() {
            Some(size) => self.values.checked_mul(size as u64)?,
            None => self.text_bytes,
        };
        usize::try_from(b).ok().filter(|&b| b <= limit)
    }
}

/// Where a stretch of one object's values lies: `count` values `stride` bytes apart from
/// `start`, repeated `chunks` times `chunk_bytes` apart.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Run {
    start: usize,
    chunks: usize,
    chunk_bytes: usize,
    count: usize,
    stride: usize,
    dtype: DataType,
    big_endian: bool,
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

/// A segment's lead-in, resolved to byte positions in the file.
#[derive(Debug, Clone, Copy)]
struct LeadIn {
    segment: usize,
    toc: u32,
    big_endian: bool,
    meta_start: usize,
    raw_start: usize,
    end: usize,
}

/// The segment's active objects: index into `objects` and this segment's raw data index.
type ObjectList = Vec<(usize, Option<RawIndex>)>;

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

    /// Reads a segment's metadata into the objects and the object list.
    fn read_metadata(&mut self, lead: &LeadIn, list: &mut ObjectList) -> Result<(), TdmsError> {
        let mut c = Cursor {
            bytes: self.bytes,
            pos: lead.meta_start,
            end: lead.raw_start,
            big_endian: lead.big_endian,
        };
        let fail = |c: &Cursor, reason: String| TdmsError::Metadata {
            segment: lead.segment,
            offset: c.pos,
            reason,
        };
        if lead.toc & TOC_NEW_OBJ_LIST != 0 {
            list.clear();
        }
        let count = c.u32().map_err(|r| fail(&c, r))?;
        for _ in 0..count {
            let path_text = c.string().map_err(|r| fail(&c, r))?;
            let path = parse_path(&path_text)
                .ok_or_else(|| fail(&c, format!("object path {path_text:?} is not a TDMS path")))?;
            let key = path_key(&path);
            let index = match self.by_path.get(&key) {
                Some(&i) => i,
                None => {
                    self.objects.push(Object {
                        path,
                        ..Object::default()
                    });
                    self.by_path.insert(key, self.objects.len() - 1);
                    self.objects.len() - 1
                }
            };
            self.read_raw_index(&mut c, lead, index, &path_text, list)?;
            let properties = c.u32().map_err(|r| fail(&c, r))?;
            for _ in 0..properties {
                let name = c.string().map_err(|r| fail(&c, r))?;
                let code = c.u32().map_err(|r| fail(&c, r))?;
                let value = c
                    .property(code)
                    .map_err(|r| fail(&c, format!("property {name:?} of {path_text}: {r}")))?;
                self.objects[index].set_property(name, value);
            }
        }
        Ok(())
    }

    /// Reads one object's raw data index and updates the object list.
    fn read_raw_index(
        &mut self,
        c: &mut Cursor<'_>,
        lead: &LeadIn,
        index: usize,
        path: &str,
        list: &mut ObjectList,
    ) -> Result<(), TdmsError> {
        let fail = |c: &Cursor, reason: String| TdmsError::Metadata {
            segment: lead.segment,
            offset: c.pos,
            reason,
        };
        let header = c.u32().map_err(|r| fail(c, r))?;
        let raw = match header {
            INDEX_NONE => None,
            INDEX_SAME => Some(self.objects[index].last_index.ok_or_else(|| {
                fail(
                    c,
                    format!("{path} has raw data 'as before', but no earlier segment gave it any"),
                )
            })?),
            INDEX_DAQMX_FORMAT | INDEX_DAQMX_DIGITAL => {
                return Err(TdmsError::DaqmxRaw {
                    what: format!("channel {path}"),
                })
            }
            _ => {
                let code = c.u32().map_err(|r| fail(c, r))?;
                if code == TYPE_DAQMX {
                    return Err(TdmsError::DaqmxRaw {
                        what: format!("channel {path}"),
                    });
                }
                let dtype = DataType::from_code(code).ok_or_else(|| {
                    fail(
                        c,
                        format!("{path} has raw data of type 0x{code:X}, not a TDMS data type"),
                    )
                })?;
                let dimension = c.u32().map_err(|r| fail(c, r))?;
                if dimension != 1 {
                    return Err(fail(
                        c,
                        format!("{path} has raw data of dimension {dimension} (TDMS allows 1)"),
                    ));
                }
                let values = c.u64().map_err(|r| fail(c, r))?;
                let text_bytes = if dtype == DataType::Text {
                    c.u64().map_err(|r| fail(c, r))?
                } else {
                    0
                };
                let raw = RawIndex {
                    dtype,
                    values,
                    text_bytes,
                };
                self.objects[index].last_index = Some(raw);
                Some(raw)
            }
        };
        match list.iter_mut().find(|(i, _)| *i == index) {
            Some(entry) => entry.1 = raw,
            None if raw.is_some() => list.push((index, raw)),
            None => {}
        }
        Ok(())
    }

    /// Records where each active object's values lie in a segment's raw data.
    fn place_raw_data(&mut self, lead: &LeadIn, list: &ObjectList) -> Result<(), TdmsError> {
        let size = lead.end - lead.raw_start;
        let active: Vec<(usize, RawIndex)> = list
            .iter()
            .filter_map(|&(i, raw)| raw.map(|r| (i, r)))
            .filter(|(_, r)| r.values > 0)
            .collect();
        if active.is_empty() || size == 0 {
            return Ok(());
        }
        let fail = |reason: String| TdmsError::Metadata {
            segment: lead.segment,
            offset: lead.raw_start,
            reason,
        };
        let too_big = |i: usize| {
            fail(format!(
                "{} says it has more raw data than the segment's {size} bytes",
                self.objects[i].path.join("/")
            ))
        };
        let mut layout = Vec::with_capacity(active.len());
        if lead.toc & TOC_INTERLEAVED != 0 {
            let values = active[0].1.values;
            let mut offset = 0usize;
            for &(i, raw) in &active {
                let width = raw.dtype.size().ok_or_else(|| {
                    fail(format!(
                        "{} is text, which cannot be interleaved",
                        self.objects[i].path.join("/")
                    ))
                })?;
                if raw.values != values {
                    return Err(fail(format!(
                        "interleaved channels of unequal length ({} values against {values})",
                        raw.values
                    )));
                }
                layout.push((i, raw, offset, width));
                offset += width;
            }
            let row = offset;
            let chunk = usize::try_from(values)
                .ok()
                .and_then(|v| v.checked_mul(row))
                .filter(|&b| b <= size)
                .ok_or_else(|| too_big(active[0].0))?;
            let (chunks, rest) = (size / chunk, size % chunk);
            for &(i, raw, at, _) in &layout {
                let run = Run {
                    start: lead.raw_start + at,
                    chunks,
                    chunk_bytes: chunk,
                    count: values as usize,
                    stride: row,
                    dtype: raw.dtype,
                    big_endian: lead.big_endian,
                };
                self.push_run(i, run);
                // A last chunk cut short: the rows that are whole.
                self.push_run(
                    i,
                    Run {
                        start: run.start + chunks * chunk,
                        chunks: 1,
                        count: rest / row,
                        ..run
                    },
                );
            }
            return Ok(());
        }
        let mut offset = 0usize;
        for &(i, raw) in &active {
            let bytes = raw.bytes(size).ok_or_else(|| too_big(i))?;
            layout.push((i, raw, offset, bytes));
            offset = offset
                .checked_add(bytes)
                .filter(|&b| b <= size)
                .ok_or_else(|| too_big(i))?;
        }
        let chunk = offset;
        let (chunks, rest) = (size / chunk, size % chunk);
        for &(i, raw, at, bytes) in &layout {
            let Some(width) = raw.dtype.size() else {
                self.push_run(i, text_run(lead, raw));
                continue;
            };
            let run = Run {
                start: lead.raw_start + at,
                chunks,
                chunk_bytes: chunk,
                count: bytes / width,
                stride: width,
                dtype: raw.dtype,
                big_endian: lead.big_endian,
            };
            self.push_run(i, run);
            // A last chunk cut short: each channel's values that are whole in it.
            let fits = rest.saturating_sub(at).min(bytes) / width;
            self.push_run(
                i,
                Run {
                    start: run.start + chunks * chunk,
                    chunks: 1,
                    count: fits,
                    ..run
                },
            );
        }
        Ok(())
    }

    fn push_run(&mut self, object: usize, run: Run) {
        if run.chunks > 0 && run.count > 0 {
            self.objects[object].runs.push(run);
        }
    }
}

/// A marker run for a text channel: never decoded, so that asking for it says it is text.
fn text_run(lead: &LeadIn, raw: RawIndex) -> Run {
    Run {
        start: lead.raw_start,
        chunks: 1,
        chunk_bytes: 0,
        count: 1,
        stride: 0,
        dtype: raw.dtype,
        big_endian: lead.big_endian,
    }
}

impl LeadIn {
    /// Reads and checks the lead-in of the segment at `offset`.
    fn read(bytes: &[u8], offset: usize, segment: usize) -> Result<Self, TdmsError> {
        let truncated = |end: u64| TdmsError::Truncated {
            segment,
            offset,
            end,
            file_bytes: bytes.len(),
        };
        // The tag first, so that a short file that is not TDMS is not called truncated.
        let tag = &bytes[offset..bytes.len().min(offset + 4)];
        if tag == TAG_INDEX {
            return Err(TdmsError::IndexFile);
        }
        if !TAG_DATA.starts_with(tag) {
            return Err(TdmsError::NotTdms {
                segment,
                offset,
                found: String::from_utf8_lossy(tag).into_owned(),
            });
        }
        let lead = bytes
            .get(offset..offset + LEAD_IN_BYTES)
            .ok_or_else(|| truncated((offset + LEAD_IN_BYTES) as u64))?;
        let toc = u32::from_le_bytes([lead[4], lead[5], lead[6], lead[7]]);
        let big_endian = toc & TOC_BIG_ENDIAN != 0;
        let mut c = Cursor {
            bytes: lead,
            pos: 8,
            end: LEAD_IN_BYTES,
            big_endian,
        };
        // The lead-in is whole, so these reads cannot fail.
        let version = c.u32().unwrap_or(0);
        let next = c.u64().unwrap_or(0);
        let raw = c.u64().unwrap_or(0);
        if !VERSIONS.contains(&version) {
            return Err(TdmsError::Version {
                segment,
                offset,
                version,
            });
        }
        if toc & TOC_DAQMX_RAW != 0 {
            return Err(TdmsError::DaqmxRaw {
                what: format!("segment {segment} (at byte {offset})"),
            });
        }
        let meta_start = offset + LEAD_IN_BYTES;
        let end = if next == SEGMENT_UNCLOSED {
            bytes.len()
        } else {
            let end = (meta_start as u64).saturating_add(next);
            if end > bytes.len() as u64 {
                return Err(truncated(end));
            }
            end as usize
        };
        let raw_start = (meta_start as u64).saturating_add(raw);
        if raw_start > end as u64 {
            return Err(truncated(raw_start));
        }
        Ok(LeadIn {
            segment,
            toc,
            big_endian,
            meta_start,
            raw_start: raw_start as usize,
            end,
        })
    }
}

/// Reads numbers and strings within `pos..end` of `bytes`, in the segment's byte order.
struct Cursor<'a> {
    bytes: &'a [u8],
    pos: usize,
    end: usize,
    big_endian: bool,
}

impl<'a> Cursor<'a> {
    fn take<const N: usize>(&mut self) -> Result<[u8; N], String> {
        let slice = self.take_slice(N)?;
        let mut out = [0u8; N];
        out.copy_from_slice(slice);
        if self.big_endian {
            out.reverse();
        }
        Ok(out)
    }

    fn take_slice(&mut self, n: usize) -> Result<&'a [u8], String> {
        if n > self.end - self.pos {
            return Err(format!(
                "needs {n} bytes but the metadata has {} left (truncated or corrupt)",
                self.end - self.pos
            ));
        }
        let slice = &self.bytes[self.pos..self.pos + n];
        self.pos += n;
        Ok(slice)
    }

    fn u32(&mut self) -> Result<u32, String> {
        Ok(u32::from_le_bytes(self.take()?))
    }

    fn u64(&mut self) -> Result<u64, String> {
        Ok(u64::from_le_bytes(self.take()?))
    }

    fn string(&mut self) -> Result<String, String> {
        let n = self.u32()? as usize;
        Ok(String::from_utf8_lossy(self.take_slice(n)?).into_owned())
    }

    fn timestamp(&mut self) -> Result<Timestamp, String> {
        // Little-endian: the fraction, then the seconds; big-endian: the other way round.
        let (fraction, seconds) = if self.big_endian {
            let s = i64::from_le_bytes(self.take()?);
            (u64::from_le_bytes(self.take()?), s)
        } else {
            let f = u64::from_le_bytes(self.take()?);
            (f, i64::from_le_bytes(self.take()?))
        };
        Ok(Timestamp { seconds, fraction })
    }

    fn property(&mut self, code: u32) -> Result<Property, String> {
        let dtype = DataType::from_code(code)
            .ok_or_else(|| format!("type 0x{code:X} is not a TDMS property type"))?;
        Ok(match dtype {
            DataType::I8 => Property::Int(i64::from(i8::from_le_bytes(self.take()?))),
            DataType::I16 => Property::Int(i64::from(i16::from_le_bytes(self.take()?))),
            DataType::I32 => Property::Int(i64::from(i32::from_le_bytes(self.take()?))),
            DataType::I64 => Property::Int(i64::from_le_bytes(self.take()?)),
            DataType::U8 => Property::UInt(u64::from(u8::from_le_bytes(self.take()?))),
            DataType::U16 => Property::UInt(u64::from(u16::from_le_bytes(self.take()?))),
            DataType::U32 => Property::UInt(u64::from(u32::from_le_bytes(self.take()?))),
            DataType::U64 => Property::UInt(u64::from_le_bytes(self.take()?)),
            DataType::F32 => Property::Float(f64::from(f32::from_le_bytes(self.take()?))),
            DataType::F64 => Property::Float(f64::from_le_bytes(self.take()?)),
            DataType::Bool => Property::Bool(self.take::<1>()?[0] != 0),
            DataType::Timestamp => Property::Time(self.timestamp()?),
            DataType::Text => Property::Text(self.string()?),
            DataType::Opaque(n) => {
                self.take_slice(n)?;
                Property::Other
            }
        })
    }
}

/// Appends a run's values to `out`. Runs were placed within the file's bytes.
fn decode_run(bytes: &[u8], run: &Run, out: &mut Vec<f64>) {
    out.reserve(run.chunks * run.count);
    for k in 0..run.chunks {
        let base = run.start + k * run.chunk_bytes;
        for i in 0..run.count {
            let at = base + i * run.stride;
            out.push(decode_value(bytes, at, run.dtype, run.big_endian));
        }
    }
}

fn decode_value(bytes: &[u8], at: usize, dtype: DataType, big_endian: bool) -> f64 {
    fn get<const N: usize>(bytes: &[u8], at: usize, big_endian: bool) -> [u8; N] {
        let mut b = [0u8; N];
        if let Some(s) = bytes.get(at..at + N) {
            b.copy_from_slice(s);
        }
        if big_endian {
            b.reverse();
        }
        b
    }
    match dtype {
        DataType::I8 => f64::from(i8::from_le_bytes(get(bytes, at, big_endian))),
        DataType::I16 => f64::from(i16::from_le_bytes(get(bytes, at, big_endian))),
        DataType::I32 => f64::from(i32::from_le_bytes(get(bytes, at, big_endian))),
        DataType::I64 => i64::from_le_bytes(get(bytes, at, big_endian)) as f64,
        DataType::U8 | DataType::Bool => f64::from(get::<1>(bytes, at, big_endian)[0]),
        DataType::U16 => f64::from(u16::from_le_bytes(get(bytes, at, big_endian))),
        DataType::U32 => f64::from(u32::from_le_bytes(get(bytes, at, big_endian))),
        DataType::U64 => u64::from_le_bytes(get(bytes, at, big_endian)) as f64,
        DataType::F32 => f64::from(f32::from_le_bytes(get(bytes, at, big_endian))),
        DataType::F64 => f64::from_le_bytes(get(bytes, at, big_endian)),
        DataType::Timestamp => {
            let mut c = Cursor {
                bytes,
                pos: at,
                end: bytes.len().min(at + 16),
                big_endian,
            };
            c.timestamp().map(|t| t.as_seconds()).unwrap_or(f64::NAN)
        }
        DataType::Text | DataType::Opaque(_) => f64::NAN,
    }
}

/// An object's linear scales as a chain to apply first to last, `None` when it has no scales
/// (or says its data is already scaled).
fn linear_scales(o: &Object) -> Result<Option<Vec<(f64, f64)>>, String> {
    let declared = o.property("NI_Number_Of_Scales").and_then(Property::as_f64);
    let typed = o
        .properties
        .iter()
        .filter_map(|(n, _)| scale_index(n))
        .max()
        .map(|m| m as f64 + 1.0);
    let Some(count) = declared.or(typed).filter(|&n| n >= 1.0) else {
        return Ok(None);
    };
    if matches!(o.property("NI_Scaling_Status"), Some(Property::Text(s)) if s == "scaled") {
        return Ok(None);
    }
    // Each scale needs a type property: a count beyond the properties there is garbage.
    if count > o.properties.len() as f64 {
        return Err(format!(
            "NI_Number_Of_Scales is {count}, more than the channel's {} properties",
            o.properties.len()
        ));
    }
    let count = count as u64;
    let mut chain = Vec::new();
    let mut scale = count - 1;
    loop {
        if chain.len() as u64 >= count {
            return Err("its scales' input sources form a loop".into());
        }
        let key = |what: &str| format!("NI_Scale[{scale}]_{what}");
        match o.property(&key("Scale_Type")) {
            Some(Property::Text(t)) if t == "Linear" => {}
            Some(Property::Text(t)) => {
                return Err(format!(
                    "scale {scale} is of type {t:?}; dlw applies Linear scales only (export scaled data)"
                ))
            }
            _ => {
                return Err(format!(
                    "scale {scale} has no NI_Scale[{scale}]_Scale_Type (a DAQmx scaler?); export scaled data"
                ))
            }
        }
        let number = |what: &str| {
            o.property(&key(what))
                .and_then(Property::as_f64)
                .filter(|v| v.is_finite())
                .ok_or_else(|| format!("scale {scale} has no finite {}", key(what)))
        };
        chain.push((number("Linear_Slope")?, number("Linear_Y_Intercept")?));
        let source = o
            .property(&key("Linear_Input_Source"))
            .and_then(Property::as_f64)
            .map_or(SOURCE_RAW, |v| v as u64);
        if source == SOURCE_RAW {
            break;
        }
        if source >= count {
            return Err(format!(
                "scale {scale}'s input source {source} is not one of its {count} scales"
            ));
        }
        scale = source;
    }
    chain.reverse();
    Ok(Some(chain))
}

/// `n` of a property named `NI_Scale[n]_Scale_Type`.
fn scale_index(name: &str) -> Option<u64> {
    name.strip_prefix("NI_Scale[")?
        .strip_suffix("]_Scale_Type")?
        .parse()
        .ok()
}

/// The components of an object path: `/` is `[]`, `/'Group'` is `[Group]`,
/// `/'Group'/'Channel'` is `[Group, Channel]`; `''` inside quotes is one quote.
fn parse_path(path: &str) -> Option<Vec<String>> {
    if path == "/" {
        return Some(Vec::new());
    }
    let mut parts = Vec::new();
    let mut chars = path.chars().peekable();
    while chars.peek().is_some() {
        if chars.next()? != '/' || chars.next()? != '\'' {
            return None;
        }
        let mut part = String::new();
        loop {
            match chars.next()? {
                '\'' if chars.peek() == Some(&'\'') => {
                    chars.next();
                    part.push('\'');
                }
                '\'' => break,
                ch => part.push(ch),
            }
        }
        parts.push(part);
    }
    (parts.len() <= 2).then_some(parts)
}

/// A lookup key for an object path (components joined by a character TDMS names cannot hold
/// unescaped).
fn path_key(path: &[String]) -> String {
    path.join("\u{0}")
}

/// The channels asked for from the TDMS file `bytes`, on one time base starting at 0: from
/// `time_column` (a channel) if given, else `rate_hz` if given, else the channels'
/// `wf_increment`, else a channel named `time_s`, `time`, `Time` or `t`.
///
/// # Errors
/// [`TdmsError`] naming the channel and the value.
pub fn daq_table(
    bytes: &[u8],
    channels: &[&str],
    time_column: Option<&str>,
    rate_hz: Option<f64>,
) -> Result<DaqTable, TdmsError> {
    let file = TdmsFile::parse(bytes)?;
    let ids: Vec<ChannelId> = channels
        .iter()
        .map(|c| file.find(c))
        .collect::<Result<_, _>>()?;
    let mut columns = Vec::with_capacity(ids.len());
    for &id in &ids {
        let values = file.values(id)?;
        if let Some(first) = columns.first().map(Vec::len) {
            if values.len() != first {
                return Err(TdmsError::Lengths {
                    first: file.name(ids[0]),
                    first_len: first,
                    other: file.name(id),
                    other_len: values.len(),
                });
            }
        }
        columns.push(values);
    }
    let n = columns.first().map_or(0, Vec::len);
    if n < MIN_ROWS {
        return Err(TdmsError::TooShort {
            rows: n,
            min: MIN_ROWS,
        });
    }
    let time_s = time_base(&file, &ids, n, time_column, rate_hz)?;
    Ok(DaqTable {
        time_s,
        channels: columns,
    })
}

/// The time of `n` samples of channels `ids` (s from the first), as [`daq_table`] chooses it.
fn time_base(
    file: &TdmsFile<'_>,
    ids: &[ChannelId],
    n: usize,
    time_column: Option<&str>,
    rate_hz: Option<f64>,
) -> Result<Vec<f64>, TdmsError> {
    let regular = |dt: f64, what: String| {
        if dt.is_finite() && dt > 0.0 {
            Ok((0..n).map(|i| i as f64 * dt).collect())
        } else {
            Err(TdmsError::Rate { what, value: dt })
        }
    };
    if let Some(name) = time_column {
        return time_channel(file, file.find(name)?, n, &file.name(ids[0]));
    }
    if let Some(hz) = rate_hz {
        return regular(1.0 / hz, format!("--daq-rate-hz {hz} gives an interval of"));
    }
    let increments: Vec<Option<f64>> = ids
        .iter()
        .map(|&id| file.waveform(id).increment_s)
        .collect();
    if let Some(dt) = increments[0] {
        for (k, inc) in increments.iter().enumerate().skip(1) {
            let other = inc.unwrap_or(f64::NAN);
            if !((other - dt).abs() <= INCREMENT_TOLERANCE * dt.abs()) {
                return Err(TdmsError::Increments {
                    first: file.name(ids[0]),
                    first_s: dt,
                    other: file.name(ids[k]),
                    other_s: other,
                });
            }
        }
        return regular(dt, format!("{}'s wf_increment", file.name(ids[0])));
    }
    let named = TIME_NAMES.iter().find_map(|t| file.find(t).ok());
    match named {
        Some(id) => time_channel(file, id, n, &file.name(ids[0])),
        None => Err(TdmsError::NoTime),
    }
}

/// A time channel's values from its first, checked to increase and to match the data's length.
fn time_channel(
    file: &TdmsFile<'_>,
    id: ChannelId,
    n: usize,
    data_channel: &str,
) -> Result<Vec<f64>, TdmsError> {
    let raw = file.values(id)?;
    if raw.len() != n {
        return Err(TdmsError::Lengths {
            first: data_channel.to_owned(),
            first_len: n,
            other: file.name(id),
            other_len: raw.len(),
        });
    }
    let t0 = raw[0];
    let time_s: Vec<f64> = raw.iter().map(|t| t - t0).collect();
    if let Some(i) = time_s.windows(2).position(|w| w[1] <= w[0]) {
        return Err(TdmsError::Time {
            channel: file.name(id),
            index: i + 1,
            time_s: time_s[i + 1],
            previous_s: time_s[i],
        });
    }
    Ok(time_s)
}

#[cfg(test)]
mod tests {
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

    /// Metadata listing `objects` as (path, Some((type code, values)) or None, properties);
    /// type code 0 writes "same as before".
    fn meta(objects: &[(&str, Option<(u32, u64)>, &[(&str, P)])]) -> Vec<u8> {
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
