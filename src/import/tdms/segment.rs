//! The segments of a TDMS file: lead-ins, metadata (objects, raw data indexes, properties) and
//! where each object's values lie in the raw data; and decoding those values.

use super::{path_key, Object, Property, TdmsError, TdmsFile, Timestamp};

/// A data file's lead-in tag.
pub(super) const TAG_DATA: &[u8; 4] = b"TDSm";
/// An index file's (`.tdms_index`) lead-in tag.
pub(super) const TAG_INDEX: &[u8; 4] = b"TDSh";
/// The lead-in's length (bytes).
pub(super) const LEAD_IN_BYTES: usize = 28;
/// `kTocMetaData`: the segment has metadata.
pub(super) const TOC_META_DATA: u32 = 1 << 1;
/// `kTocNewObjList`: the segment's object list replaces the last one.
pub(super) const TOC_NEW_OBJ_LIST: u32 = 1 << 2;
/// `kTocRawData`: the segment has raw data.
pub(super) const TOC_RAW_DATA: u32 = 1 << 3;
/// `kTocInterleavedData`: the raw data is interleaved.
pub(super) const TOC_INTERLEAVED: u32 = 1 << 5;
/// `kTocBigEndian`: the segment's numbers (not the table of contents) are big-endian.
pub(super) const TOC_BIG_ENDIAN: u32 = 1 << 6;
/// `kTocDAQmxRawData`: the segment holds DAQmx raw data.
pub(super) const TOC_DAQMX_RAW: u32 = 1 << 7;
/// The format versions NI has published.
pub(super) const VERSIONS: [u32; 2] = [4712, 4713];
/// Raw data index: the same as the object's in the last segment.
pub(super) const INDEX_SAME: u32 = 0x0000_0000;
/// Raw data index: no raw data in this segment.
pub(super) const INDEX_NONE: u32 = 0xFFFF_FFFF;
/// Raw data index: DAQmx format changing scaler.
pub(super) const INDEX_DAQMX_FORMAT: u32 = 0x6912_0000;
/// Raw data index: DAQmx digital line scaler.
pub(super) const INDEX_DAQMX_DIGITAL: u32 = 0x6913_0000;
/// Data type code of DAQmx raw data.
pub(super) const TYPE_DAQMX: u32 = 0xFFFF_FFFF;
/// Next segment offset of a segment its writer never closed.
pub(super) const SEGMENT_UNCLOSED: u64 = u64::MAX;
/// A raw data type.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum DataType {
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
pub(super) struct RawIndex {
    pub(super) dtype: DataType,
    /// The data type's code as written (0x19 and 0x09 both decode as f32).
    pub(super) code: u32,
    pub(super) values: u64,
    /// For text: the bytes of the segment's strings and their offsets.
    pub(super) text_bytes: u64,
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
pub(super) struct Run {
    pub(super) start: usize,
    pub(super) chunks: usize,
    pub(super) chunk_bytes: usize,
    pub(super) count: usize,
    pub(super) stride: usize,
    pub(super) dtype: DataType,
    /// The data type's code as written.
    pub(super) code: u32,
    pub(super) big_endian: bool,
}

/// A segment's lead-in, resolved to byte positions in the file.
#[derive(Debug, Clone, Copy)]
pub(super) struct LeadIn {
    pub(super) segment: usize,
    pub(super) toc: u32,
    pub(super) big_endian: bool,
    pub(super) meta_start: usize,
    pub(super) raw_start: usize,
    pub(super) end: usize,
}

/// The segment's active objects: index into `objects` and this segment's raw data index.
pub(super) type ObjectList = Vec<(usize, Option<RawIndex>)>;

impl<'a> TdmsFile<'a> {
    /// Reads a segment's metadata into the objects and the object list.
    pub(super) fn read_metadata(
        &mut self,
        lead: &LeadIn,
        list: &mut ObjectList,
    ) -> Result<(), TdmsError> {
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
                    code,
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
    pub(super) fn place_raw_data(
        &mut self,
        lead: &LeadIn,
        list: &ObjectList,
    ) -> Result<(), TdmsError> {
        let size = lead.end - lead.raw_start;
        let active: Vec<(usize, RawIndex)> = list
            .iter()
            .filter_map(|&(i, raw)| raw.map(|r| (i, r)))
            .filter(|(_, r)| r.values > 0)
            .collect();
        if active.is_empty() || size == 0 {
            return Ok(());
        }
        if lead.toc & TOC_INTERLEAVED != 0 {
            self.place_interleaved(lead, &active, size)
        } else {
            self.place_contiguous(lead, &active, size)
        }
    }

    /// Interleaved raw data: one value of each channel per row, rows in chunks of `values`.
    fn place_interleaved(
        &mut self,
        lead: &LeadIn,
        active: &[(usize, RawIndex)],
        size: usize,
    ) -> Result<(), TdmsError> {
        let mut layout = Vec::with_capacity(active.len());
        let values = active[0].1.values;
        let mut offset = 0usize;
        for &(i, raw) in active {
            let width = raw.dtype.size().ok_or_else(|| {
                raw_data_error(
                    lead,
                    format!(
                        "{} is text, which cannot be interleaved",
                        self.objects[i].path.join("/")
                    ),
                )
            })?;
            if raw.values != values {
                return Err(raw_data_error(
                    lead,
                    format!(
                        "interleaved channels of unequal length ({} values against {values})",
                        raw.values
                    ),
                ));
            }
            layout.push((i, raw, offset));
            offset += width;
        }
        let row = offset;
        let chunk = usize::try_from(values)
            .ok()
            .and_then(|v| v.checked_mul(row))
            .filter(|&b| b <= size)
            .ok_or_else(|| self.too_big(lead, active[0].0, size))?;
        let (chunks, rest) = (size / chunk, size % chunk);
        for &(i, raw, at) in &layout {
            let run = Run {
                start: lead.raw_start + at,
                chunks,
                chunk_bytes: chunk,
                count: values as usize,
                stride: row,
                dtype: raw.dtype,
                code: raw.code,
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
        Ok(())
    }

    /// Contiguous raw data: each channel's values in a block, the blocks in chunks.
    fn place_contiguous(
        &mut self,
        lead: &LeadIn,
        active: &[(usize, RawIndex)],
        size: usize,
    ) -> Result<(), TdmsError> {
        let mut layout = Vec::with_capacity(active.len());
        let mut offset = 0usize;
        for &(i, raw) in active {
            let bytes = raw.bytes(size).ok_or_else(|| self.too_big(lead, i, size))?;
            layout.push((i, raw, offset, bytes));
            offset = offset
                .checked_add(bytes)
                .filter(|&b| b <= size)
                .ok_or_else(|| self.too_big(lead, i, size))?;
        }
        let chunk = offset;
        if chunk == 0 {
            // Only empty text: nothing to place.
            return Ok(());
        }
        let (chunks, rest) = (size / chunk, size % chunk);
        for &(i, raw, at, bytes) in &layout {
            let Some(width) = raw.dtype.size() else {
                // Text: per chunk, `values` end offsets (u32) then the strings' bytes.
                self.push_run(
                    i,
                    Run {
                        start: lead.raw_start + at,
                        chunks,
                        chunk_bytes: chunk,
                        count: raw.values as usize,
                        stride: 0,
                        dtype: raw.dtype,
                        code: raw.code,
                        big_endian: lead.big_endian,
                    },
                );
                continue;
            };
            let run = Run {
                start: lead.raw_start + at,
                chunks,
                chunk_bytes: chunk,
                count: bytes / width,
                stride: width,
                dtype: raw.dtype,
                code: raw.code,
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

    /// Object `i` claims more raw data than the segment's `size` bytes.
    fn too_big(&self, lead: &LeadIn, i: usize, size: usize) -> TdmsError {
        raw_data_error(
            lead,
            format!(
                "{} says it has more raw data than the segment's {size} bytes",
                self.objects[i].path.join("/")
            ),
        )
    }

    fn push_run(&mut self, object: usize, run: Run) {
        if run.chunks > 0 && run.count > 0 {
            self.objects[object].runs.push(run);
        }
    }
}

/// An error in a segment's raw data, at its start.
fn raw_data_error(lead: &LeadIn, reason: String) -> TdmsError {
    TdmsError::Metadata {
        segment: lead.segment,
        offset: lead.raw_start,
        reason,
    }
}

/// The strings of a text run: per chunk, `count` end offsets (u32, from the strings' start)
/// then the strings' UTF-8 bytes (invalid bytes replaced). A chunk cut short gives the strings
/// that are whole in it.
pub(super) fn decode_text_run(bytes: &[u8], run: &Run, out: &mut Vec<String>) {
    for k in 0..run.chunks {
        let base = run.start + k * run.chunk_bytes;
        let strings = base + 4 * run.count;
        let mut from = 0usize;
        for i in 0..run.count {
            let at = base + 4 * i;
            let Some(b) = bytes.get(at..at + 4) else {
                return;
            };
            let mut word = [0u8; 4];
            word.copy_from_slice(b);
            if run.big_endian {
                word.reverse();
            }
            let to = u32::from_le_bytes(word) as usize;
            let Some(text) = bytes.get(strings + from..strings + to) else {
                return;
            };
            out.push(String::from_utf8_lossy(text).into_owned());
            from = to;
        }
    }
}

/// npTDMS's name of a TDMS data type code (`DoubleFloat`, `Int16`, …).
pub(super) fn type_name(code: u32) -> &'static str {
    match code {
        1 => "Int8",
        2 => "Int16",
        3 => "Int32",
        4 => "Int64",
        5 => "Uint8",
        6 => "Uint16",
        7 => "Uint32",
        8 => "Uint64",
        9 => "SingleFloat",
        10 => "DoubleFloat",
        11 => "ExtendedFloat",
        0x19 => "SingleFloatWithUnit",
        0x1A => "DoubleFloatWithUnit",
        0x1B => "ExtendedFloatWithUnit",
        0x20 => "String",
        0x21 => "Boolean",
        0x44 => "TimeStamp",
        0x0008_000C => "ComplexSingleFloat",
        0x0010_000D => "ComplexDoubleFloat",
        _ => "Unknown",
    }
}

impl LeadIn {
    /// Reads and checks the lead-in of the segment at `offset`.
    pub(super) fn read(bytes: &[u8], offset: usize, segment: usize) -> Result<Self, TdmsError> {
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
pub(super) struct Cursor<'a> {
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
pub(super) fn decode_run(bytes: &[u8], run: &Run, out: &mut Vec<f64>) {
    out.reserve(run.chunks * run.count);
    for k in 0..run.chunks {
        let base = run.start + k * run.chunk_bytes;
        for i in 0..run.count {
            let at = base + i * run.stride;
            out.push(decode_value(bytes, at, run.dtype, run.big_endian));
        }
    }
}

pub(super) fn decode_value(bytes: &[u8], at: usize, dtype: DataType, big_endian: bool) -> f64 {
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

/// The components of an object path: `/` is `[]`, `/'Group'` is `[Group]`,
/// `/'Group'/'Channel'` is `[Group, Channel]`; `''` inside quotes is one quote.
pub(super) fn parse_path(path: &str) -> Option<Vec<String>> {
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
