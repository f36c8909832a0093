//! Reading `.npz` archives with bounded memory: the ZIP directory, each
//! entry's `.npy` header read alone, then an entry's data inflated only up
//! to the bytes its header's shape and dtype need.
//!
//! Entries may be stored or deflated; ZIP64 sizes and offsets (NumPy's
//! `np.savez` writes its local headers in ZIP64) are read. Refused: a file
//! that is not a ZIP archive, an archive spanning several disks, an
//! encrypted entry or another compression method, a local header that
//! disagrees with the directory, a `.npy` header over [`MAX_HEADER`] bytes
//! or of a format other than 1.0 and 2.0, object and structured dtypes
//! (nothing is ever unpickled), an entry holding more or less data than
//! its header says, and a CRC-32 that does not match.
//!
//! ```
//! use dymsum_io::npz::{write_npz_to, Array, Data, NpzArchive};
//! let mut bytes = Vec::new();
//! write_npz_to(&mut bytes, &[Array::f64("x", vec![2, 2], vec![1.0, 2.0, 3.0, 4.0])])?;
//! let mut npz = NpzArchive::new(std::io::Cursor::new(bytes))?;
//! assert_eq!(npz.entries()[0].name, "x.npy");
//! let header = npz.header(0)?;
//! assert_eq!((header.dtype.descr(), header.shape.as_slice()), ("<f8", &[2, 2][..]));
//! assert_eq!(npz.values(0, &header)?, Data::F64(vec![1.0, 2.0, 3.0, 4.0]));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use super::Data;
use flate2::read::DeflateDecoder;
use std::io::{self, Read, Seek, SeekFrom};

/// The largest `.npy` header read (NumPy's own limit for safe loading).
pub const MAX_HEADER: u64 = 10_000;

/// What reading an archive found wrong.
#[derive(Debug, thiserror::Error)]
pub enum NpzError {
    /// Not a ZIP archive, or its directory is corrupt.
    #[error("not a NumPy .npz archive: {0}")]
    NotAnArchive(String),
    /// One entry is bad.
    #[error("entry '{entry}': {reason}")]
    Entry {
        /// The entry's name, without `.npy`.
        entry: String,
        /// What is wrong.
        reason: String,
    },
    /// The file could not be read (an error of the operating system).
    #[error(transparent)]
    Io(io::Error),
}

/// An entry of the archive's directory.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct EntryInfo {
    /// The entry's name (`x.npy` for the array `x`).
    pub name: String,
    /// The compression method: 0 stored, 8 deflated (others are refused
    /// when the entry is read).
    pub method: u16,
    /// Whether the entry is encrypted (refused when read).
    pub encrypted: bool,
    crc: u32,
    compressed: u64,
    size: u64,
    local_offset: u64,
}

impl EntryInfo {
    /// The name without `.npy` (the array's name), or the whole name.
    pub fn array_name(&self) -> &str {
        self.name.strip_suffix(".npy").unwrap_or(&self.name)
    }
}

/// A dtype as an `.npy` header gives it: kind, item size and byte order.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Dtype {
    /// NumPy's kind: `b` bool, `i` signed, `u` unsigned, `f` float, `c`
    /// complex, `U` unicode, `S` bytes, `V` raw, `M`/`m` dates and times.
    pub kind: char,
    /// Bytes per element (4 per character for `U`).
    pub itemsize: usize,
    /// Whether the elements are big-endian.
    pub big_endian: bool,
    descr: String,
}

impl Dtype {
    /// The dtype of `descr` (`'<f8'`, `'|i1'`, `'>U3'`, ...: NumPy's
    /// `dtype.str`).
    ///
    /// # Errors
    /// The reason, for anything else: an object dtype ("object arrays are
    /// never read"), a descr that is not a dtype.
    pub fn parse(descr: &str) -> Result<Dtype, String> {
        let (order, rest) = match descr.chars().next() {
            Some(c @ ('<' | '>' | '|' | '=')) => (c, &descr[1..]),
            _ => ('=', descr),
        };
        let mut chars = rest.chars();
        let kind = chars
            .next()
            .ok_or_else(|| format!("bad .npy header (empty descr {descr:?})"))?;
        let rest = chars.as_str();
        if kind == 'O' {
            return Err(format!(
                "dtype {descr} is not a plain number or string (object arrays are never read)"
            ));
        }
        // Dates and times carry a unit: `<M8[ns]`.
        let digits = match (kind, rest.find('[')) {
            ('M' | 'm', Some(at)) if rest.ends_with(']') => &rest[..at],
            _ => rest,
        };
        let size: usize = match digits.parse() {
            Ok(n) if digits.bytes().all(|b| b.is_ascii_digit()) => n,
            _ => return Err(format!("bad .npy header (descr {descr:?} is not a dtype)")),
        };
        let fits = match kind {
            'b' => size == 1,
            'i' | 'u' | 'M' | 'm' => matches!(size, 1 | 2 | 4 | 8),
            'f' => matches!(size, 2 | 4 | 8 | 12 | 16),
            'c' => matches!(size, 8 | 16 | 24 | 32),
            'S' | 'a' | 'V' => true,
            'U' => size.checked_mul(4).is_some(),
            _ => false,
        };
        if !fits {
            return Err(format!("bad .npy header (descr {descr:?} is not a dtype)"));
        }
        Ok(Dtype {
            kind: if kind == 'a' { 'S' } else { kind },
            itemsize: if kind == 'U' { 4 * size } else { size },
            big_endian: match order {
                '>' => true,
                '<' | '|' => false,
                _ => cfg!(target_endian = "big"),
            },
            descr: descr.to_string(),
        })
    }

    /// The dtype of an in-memory array's data.
    pub fn of(data: &Data) -> Dtype {
        let (kind, itemsize) = match data {
            Data::F64(_) => ('f', 8),
            Data::I64(_) => ('i', 8),
            Data::Str(v) => ('U', 4 * super::str_width(v)),
        };
        let descr = format!(
            "<{kind}{}",
            if kind == 'U' { itemsize / 4 } else { itemsize }
        );
        Dtype {
            kind,
            itemsize,
            big_endian: false,
            descr,
        }
    }

    /// The dtype as its header wrote it (NumPy's `dtype.str`).
    pub fn descr(&self) -> &str {
        &self.descr
    }
}

/// An `.npy` header: the dtype, the shape, the order and where the data
/// starts.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct NpyHeader {
    /// The elements' dtype.
    pub dtype: Dtype,
    /// The shape; empty for a scalar.
    pub shape: Vec<u64>,
    /// Whether the data is in Fortran (column-major) order.
    pub fortran_order: bool,
    /// The bytes before the data: magic, version, length and header.
    pub data_offset: u64,
}

impl NpyHeader {
    /// The number of elements, `None` if it overflows.
    pub fn count(&self) -> Option<u64> {
        self.shape.iter().try_fold(1u64, |n, &d| n.checked_mul(d))
    }

    /// The data's length in bytes, `None` if it overflows.
    pub fn nbytes(&self) -> Option<u64> {
        self.count()?.checked_mul(self.dtype.itemsize as u64)
    }

    /// The values of `data` (exactly [`NpyHeader::nbytes`] bytes) in C
    /// order and native byte order: signed integers as `I64`, floats of 4
    /// or 8 bytes as `F64`, unicode as `Str` (trailing NULs stripped, as
    /// NumPy does).
    ///
    /// # Errors
    /// The reason, for data of another length, any other dtype, or a
    /// character that is not a Unicode scalar value.
    pub fn decode(&self, data: &[u8]) -> Result<Data, String> {
        if Some(data.len() as u64) != self.nbytes() {
            return Err(format!(
                "{} data bytes where the shape {} of {} needs {:?}",
                data.len(),
                shape_text(&self.shape),
                self.dtype.descr,
                self.nbytes()
            ));
        }
        let mut values = self.no_values()?;
        self.decode_items(data, &mut values)?;
        Ok(self.in_c_order(values))
    }

    /// No values yet, in the variant the dtype decodes to; `Err` for a
    /// dtype that is not read.
    fn no_values(&self) -> Result<Data, String> {
        let d = &self.dtype;
        match (d.kind, d.itemsize) {
            ('i', 1 | 2 | 4 | 8) => Ok(Data::I64(Vec::new())),
            ('f', 4 | 8) => Ok(Data::F64(Vec::new())),
            ('U', 0) => Err(format!("dtype {} holds no characters", d.descr)),
            ('U', _) => Ok(Data::Str(Vec::new())),
            _ => Err(format!(
                "dtype {} is not read (int, float or unicode)",
                d.descr
            )),
        }
    }

    /// Appends the values of `bytes`, whole items of the dtype, to `out`
    /// (of [`NpyHeader::no_values`]'s variant).
    fn decode_items(&self, bytes: &[u8], out: &mut Data) -> Result<(), String> {
        let d = &self.dtype;
        let be = d.big_endian;
        let n = d.itemsize;
        // `chunks_exact(N)` gives N bytes: the conversions cannot fail.
        fn bytes_of<const N: usize>(b: &[u8]) -> [u8; N] {
            b.try_into().unwrap_or([0; N])
        }
        match (out, n) {
            (Data::F64(v), 8) => v.extend(bytes.chunks_exact(8).map(|b| {
                let b = bytes_of::<8>(b);
                if be {
                    f64::from_be_bytes(b)
                } else {
                    f64::from_le_bytes(b)
                }
            })),
            (Data::F64(v), 4) => v.extend(bytes.chunks_exact(4).map(|b| {
                let b = bytes_of::<4>(b);
                f64::from(if be {
                    f32::from_be_bytes(b)
                } else {
                    f32::from_le_bytes(b)
                })
            })),
            (Data::I64(v), 8) => v.extend(bytes.chunks_exact(8).map(|b| {
                let b = bytes_of::<8>(b);
                if be {
                    i64::from_be_bytes(b)
                } else {
                    i64::from_le_bytes(b)
                }
            })),
            (Data::I64(v), 4) => v.extend(bytes.chunks_exact(4).map(|b| {
                let b = bytes_of::<4>(b);
                i64::from(if be {
                    i32::from_be_bytes(b)
                } else {
                    i32::from_le_bytes(b)
                })
            })),
            (Data::I64(v), 2) => v.extend(bytes.chunks_exact(2).map(|b| {
                let b = bytes_of::<2>(b);
                i64::from(if be {
                    i16::from_be_bytes(b)
                } else {
                    i16::from_le_bytes(b)
                })
            })),
            (Data::I64(v), 1) => v.extend(bytes.iter().map(|&b| i64::from(b as i8))),
            (Data::Str(v), _) => {
                for item in bytes.chunks_exact(n) {
                    let mut s = String::with_capacity(n / 4);
                    for c in item.chunks_exact(4) {
                        let c = bytes_of::<4>(c);
                        let code = if be {
                            u32::from_be_bytes(c)
                        } else {
                            u32::from_le_bytes(c)
                        };
                        s.push(char::from_u32(code).ok_or_else(|| {
                            format!("holds the code point {code:#x}, not a Unicode character")
                        })?);
                    }
                    s.truncate(s.trim_end_matches('\0').len());
                    v.push(s);
                }
            }
            _ => return Err(format!("dtype {} is not read", d.descr)),
        }
        Ok(())
    }

    /// `values` in C order (they are in the header's order).
    fn in_c_order(&self, values: Data) -> Data {
        if self.fortran_order {
            c_order(values, &self.shape)
        } else {
            values
        }
    }
}

/// Reads into `buf` until it is full or the stream ends; the bytes read.
fn fill(f: &mut dyn Read, buf: &mut [u8]) -> io::Result<usize> {
    let mut got = 0;
    while got < buf.len() {
        match f.read(&mut buf[got..]) {
            Ok(0) => break,
            Ok(k) => got += k,
            Err(e) if e.kind() == io::ErrorKind::Interrupted => {}
            Err(e) => return Err(e),
        }
    }
    Ok(got)
}

/// A shape as Python writes a tuple: `()`, `(3,)`, `(2, 3)`.
pub fn shape_text(shape: &[u64]) -> String {
    match shape {
        [n] => format!("({n},)"),
        s => format!(
            "({})",
            s.iter()
                .map(|n| n.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

/// The values of a Fortran-ordered array in C order.
fn c_order(values: Data, shape: &[u64]) -> Data {
    if shape.len() < 2 {
        return values;
    }
    let shape: Vec<usize> = shape.iter().map(|&d| d as usize).collect();
    fn permute<T: Clone>(v: Vec<T>, shape: &[usize]) -> Vec<T> {
        let mut out = Vec::with_capacity(v.len());
        let mut index = vec![0usize; shape.len()];
        // Column-major strides.
        let mut stride = vec![1usize; shape.len()];
        for k in 1..shape.len() {
            stride[k] = stride[k - 1] * shape[k - 1];
        }
        for _ in 0..v.len() {
            let at: usize = index.iter().zip(&stride).map(|(i, s)| i * s).sum();
            out.push(v[at].clone());
            // The C-order odometer: the last index turns fastest.
            for k in (0..shape.len()).rev() {
                index[k] += 1;
                if index[k] < shape[k] {
                    break;
                }
                index[k] = 0;
            }
        }
        out
    }
    match values {
        Data::F64(v) => Data::F64(permute(v, &shape)),
        Data::I64(v) => Data::I64(permute(v, &shape)),
        Data::Str(v) => Data::Str(permute(v, &shape)),
    }
}

/// An `.npz` archive being read (module docs).
#[derive(Debug)]
pub struct NpzArchive<R> {
    reader: R,
    len: u64,
    entries: Vec<EntryInfo>,
}

fn le16(b: &[u8], at: usize) -> u16 {
    u16::from_le_bytes([b[at], b[at + 1]])
}

fn le32(b: &[u8], at: usize) -> u32 {
    u32::from_le_bytes(b[at..at + 4].try_into().expect("four bytes"))
}

fn le64(b: &[u8], at: usize) -> u64 {
    u64::from_le_bytes(b[at..at + 8].try_into().expect("eight bytes"))
}

/// An I/O error: the operating system's stays one; anything else (a short
/// read, a corrupt deflate stream) says what is wrong with `entry`.
fn entry_io(entry: &str, e: io::Error) -> NpzError {
    if e.raw_os_error().is_some() {
        NpzError::Io(e)
    } else if e.kind() == io::ErrorKind::UnexpectedEof {
        NpzError::Entry {
            entry: entry.into(),
            reason: "truncated (an .npy entry)".into(),
        }
    } else {
        NpzError::Entry {
            entry: entry.into(),
            reason: format!("corrupt data ({e})"),
        }
    }
}

impl<R: Read + Seek> NpzArchive<R> {
    /// Reads the archive's directory (not its entries).
    ///
    /// # Errors
    /// [`NpzError::NotAnArchive`] when there is no ZIP end record or the
    /// directory is corrupt or spans several disks; [`NpzError::Io`] when
    /// reading fails.
    pub fn new(mut reader: R) -> Result<NpzArchive<R>, NpzError> {
        let not = |m: &str| NpzError::NotAnArchive(m.to_string());
        let io = |e: io::Error| {
            if e.raw_os_error().is_some() {
                NpzError::Io(e)
            } else {
                NpzError::NotAnArchive(e.to_string())
            }
        };
        let len = reader.seek(SeekFrom::End(0)).map_err(io)?;
        if len < 22 {
            return Err(not("too short for a ZIP archive"));
        }
        // The end record: 22 bytes and a comment of at most 65,535.
        let tail_len = len.min(22 + 65_535);
        let mut tail = vec![0u8; tail_len as usize];
        reader.seek(SeekFrom::Start(len - tail_len)).map_err(io)?;
        reader.read_exact(&mut tail).map_err(io)?;
        let at = (0..=tail.len() - 22)
            .rev()
            .find(|&i| tail[i..i + 4] == [0x50, 0x4b, 0x05, 0x06])
            .ok_or_else(|| not("no ZIP end record"))?;
        let end = &tail[at..at + 22];
        let end_offset = len - tail_len + at as u64;
        if le16(end, 4) != 0 || le16(end, 6) != 0 {
            return Err(not("an archive spanning several disks"));
        }
        let mut count = u64::from(le16(end, 10));
        let mut cd_size = u64::from(le32(end, 12));
        let mut cd_offset = u64::from(le32(end, 16));
        // ZIP64: a locator just before the end record points at the
        // ZIP64 end record, which holds the full-width values.
        if end_offset >= 20 {
            let mut loc = [0u8; 20];
            reader.seek(SeekFrom::Start(end_offset - 20)).map_err(io)?;
            reader.read_exact(&mut loc).map_err(io)?;
            if loc[..4] == [0x50, 0x4b, 0x06, 0x07] {
                let at64 = le64(&loc, 8);
                if at64.checked_add(56).is_none_or(|e| e > end_offset - 20) {
                    return Err(not("a ZIP64 end record out of the file"));
                }
                let mut rec = [0u8; 56];
                reader.seek(SeekFrom::Start(at64)).map_err(io)?;
                reader.read_exact(&mut rec).map_err(io)?;
                if rec[..4] != [0x50, 0x4b, 0x06, 0x06] {
                    return Err(not("a bad ZIP64 end record"));
                }
                count = le64(&rec, 32);
                cd_size = le64(&rec, 40);
                cd_offset = le64(&rec, 48);
            }
        }
        if cd_offset
            .checked_add(cd_size)
            .is_none_or(|e| e > end_offset)
        {
            return Err(not("a central directory out of the file"));
        }
        let mut cd = vec![0u8; cd_size as usize];
        reader.seek(SeekFrom::Start(cd_offset)).map_err(io)?;
        reader.read_exact(&mut cd).map_err(io)?;
        let mut entries = Vec::new();
        let mut p = 0usize;
        while p < cd.len() {
            if cd.len() - p < 46 || le32(&cd, p) != 0x0201_4b50 {
                return Err(not("a bad central directory entry"));
            }
            let h = &cd[p..p + 46];
            let (n, x, c) = (
                le16(h, 28) as usize,
                le16(h, 30) as usize,
                le16(h, 32) as usize,
            );
            if cd.len() - p - 46 < n + x + c {
                return Err(not("a bad central directory entry"));
            }
            let name = String::from_utf8_lossy(&cd[p + 46..p + 46 + n]).into_owned();
            let mut size = u64::from(le32(h, 24));
            let mut compressed = u64::from(le32(h, 20));
            let mut local_offset = u64::from(le32(h, 42));
            // The ZIP64 extra field: the values saturated above, in order.
            let mut extra = &cd[p + 46 + n..p + 46 + n + x];
            while extra.len() >= 4 {
                let (id, k) = (le16(extra, 0), le16(extra, 2) as usize);
                let body = extra
                    .get(4..4 + k)
                    .ok_or_else(|| not("a bad extra field"))?;
                if id == 1 {
                    let mut q = 0;
                    for v in [&mut size, &mut compressed, &mut local_offset] {
                        if *v == 0xFFFF_FFFF {
                            if body.len() < q + 8 {
                                return Err(not("a bad ZIP64 extra field"));
                            }
                            *v = le64(body, q);
                            q += 8;
                        }
                    }
                }
                extra = &extra[4 + k..];
            }
            entries.push(EntryInfo {
                name,
                method: le16(h, 10),
                encrypted: le16(h, 8) & 1 != 0,
                crc: le32(h, 16),
                compressed,
                size,
                local_offset,
            });
            p += 46 + n + x + c;
        }
        if entries.len() as u64 != count {
            return Err(not(
                "the end record's count of entries is not the directory's",
            ));
        }
        Ok(NpzArchive {
            reader,
            len,
            entries,
        })
    }

    /// The directory's entries, in order (a name may repeat).
    pub fn entries(&self) -> &[EntryInfo] {
        &self.entries
    }

    /// A reader of entry `i`'s uncompressed bytes (at most what the
    /// deflate stream or the stored bytes hold).
    fn open(&mut self, i: usize) -> Result<Box<dyn Read + '_>, NpzError> {
        let e = self.entries[i].clone();
        let entry = e.array_name().to_string();
        let bad = |reason: String| NpzError::Entry {
            entry: entry.clone(),
            reason,
        };
        if e.encrypted {
            return Err(bad("the entry is encrypted".into()));
        }
        if e.method != 0 && e.method != 8 {
            return Err(bad(format!("unsupported compression method {}", e.method)));
        }
        let mut local = [0u8; 30];
        let short = |e: io::Error| match entry_io(&entry, e) {
            NpzError::Io(e) => NpzError::Io(e),
            _ => bad("truncated local header".into()),
        };
        if e.local_offset
            .checked_add(30)
            .is_none_or(|end| end > self.len)
        {
            return Err(bad("its local header is out of the file".into()));
        }
        self.reader
            .seek(SeekFrom::Start(e.local_offset))
            .map_err(|e| entry_io(&entry, e))?;
        self.reader.read_exact(&mut local).map_err(short)?;
        if le32(&local, 0) != 0x0403_4b50 {
            return Err(bad("a bad local header".into()));
        }
        let (n, x) = (le16(&local, 26) as u64, le16(&local, 28) as u64);
        let mut name = vec![0u8; n as usize];
        self.reader.read_exact(&mut name).map_err(short)?;
        if name != e.name.as_bytes() {
            return Err(bad(format!(
                "the local header names {:?}, the directory {:?}",
                String::from_utf8_lossy(&name),
                e.name
            )));
        }
        let start = e.local_offset + 30 + n + x;
        if start
            .checked_add(e.compressed)
            .is_none_or(|end| end > self.len)
        {
            return Err(bad(
                "truncated (its data runs past the end of the file)".into()
            ));
        }
        self.reader
            .seek(SeekFrom::Start(start))
            .map_err(|e| entry_io(&entry, e))?;
        let raw = (&mut self.reader).take(e.compressed);
        Ok(if e.method == 8 {
            Box::new(DeflateDecoder::new(raw))
        } else {
            Box::new(raw)
        })
    }

    /// Entry `i`'s `.npy` header, read without its data: magic, format 1.0
    /// or 2.0, a header of at most [`MAX_HEADER`] bytes (its length checked
    /// before it is read), a plain dtype.
    ///
    /// # Errors
    /// [`NpzError::Entry`] for an entry that is refused (module docs) or a
    /// header that is not a plain array's; [`NpzError::Io`] when reading
    /// fails.
    pub fn header(&mut self, i: usize) -> Result<NpyHeader, NpzError> {
        let entry = self.entries[i].array_name().to_string();
        let bad = |reason: String| NpzError::Entry {
            entry: entry.clone(),
            reason,
        };
        let mut f = self.open(i)?;
        let mut exact = |n: usize, what: &str| -> Result<Vec<u8>, NpzError> {
            let mut b = vec![0u8; n];
            f.read_exact(&mut b)
                .map_err(|e| match entry_io(&entry, e) {
                    NpzError::Entry { entry, .. } => NpzError::Entry {
                        entry,
                        reason: format!("truncated {what} (an .npy entry)"),
                    },
                    other => other,
                })?;
            Ok(b)
        };
        let magic = exact(8, "magic")?;
        if magic[..6] != *b"\x93NUMPY" {
            return Err(bad("not an .npy array (bad magic)".into()));
        }
        let (hlen, lenbytes) = match (magic[6], magic[7]) {
            (1, 0) => (u64::from(le16(&exact(2, "header length")?, 0)), 2),
            (2, 0) => (u64::from(le32(&exact(4, "header length")?, 0)), 4),
            (a, b) => {
                return Err(bad(format!(
                    ".npy format version {a}.{b} is not supported (1.0 or 2.0)"
                )))
            }
        };
        if hlen > MAX_HEADER {
            return Err(bad(format!(
                ".npy header of {hlen} bytes (at most {MAX_HEADER})"
            )));
        }
        let text = exact(hlen as usize, "header")?;
        // NumPy writes the header in Latin-1 (format 1.0 and 2.0).
        let text: String = text.iter().map(|&b| b as char).collect();
        let (dtype, shape, fortran_order) = parse_header(&text).map_err(bad)?;
        Ok(NpyHeader {
            dtype,
            shape,
            fortran_order,
            data_offset: 8 + lenbytes + hlen,
        })
    }

    /// Entry `i`'s values ([`NpyHeader::decode`]), `header` being its
    /// [`NpzArchive::header`]. Memory is bounded by the header's shape and
    /// dtype: an entry whose directory size is not the header's plus the
    /// data's is refused before it is inflated, the data is decoded a
    /// megabyte at a time as it is inflated (the raw bytes are not kept),
    /// and inflating stops one byte past the data the header describes.
    /// The CRC-32 is checked.
    ///
    /// # Errors
    /// [`NpzError::Entry`] for an entry holding more or less data than its
    /// header says, a corrupt deflate stream, a CRC-32 mismatch or a dtype
    /// that is not read; [`NpzError::Io`] when reading fails.
    pub fn values(&mut self, i: usize, header: &NpyHeader) -> Result<Data, NpzError> {
        let e = self.entries[i].clone();
        let entry = e.array_name().to_string();
        let bad = |reason: String| NpzError::Entry {
            entry: entry.clone(),
            reason,
        };
        let what = || {
            format!(
                "its shape {} of {}",
                shape_text(&header.shape),
                header.dtype.descr
            )
        };
        let nbytes = header
            .nbytes()
            .filter(|&n| header.data_offset.checked_add(n).is_some())
            .ok_or_else(|| bad(format!("{} is too large", what())))?;
        let want = header.data_offset + nbytes;
        if e.size > want {
            return Err(bad(format!("holds more data than {} needs", what())));
        }
        if e.size < want {
            return Err(bad(format!(
                "truncated: {} of the {nbytes} data bytes {} needs",
                e.size.saturating_sub(header.data_offset),
                what()
            )));
        }
        let mut values = header.no_values().map_err(bad)?;
        let itemsize = header.dtype.itemsize;
        let count = usize::try_from(nbytes / itemsize as u64).unwrap_or(usize::MAX);
        // A stored entry's bytes are in the file (its directory size was
        // checked against the file's length); a deflated one's are
        // reserved as they come, past 64 MiB.
        let reserve = if e.method == 0 {
            count
        } else {
            count.min((64 << 20) / itemsize)
        };
        match &mut values {
            Data::F64(v) => v.reserve(reserve),
            Data::I64(v) => v.reserve(reserve),
            Data::Str(v) => v.reserve(reserve),
        }
        let mut f = self.open(i)?;
        let mut crc = crc32fast::Hasher::new();
        let mut head = vec![0u8; header.data_offset as usize];
        f.read_exact(&mut head).map_err(|e| entry_io(&entry, e))?;
        crc.update(&head);
        // Decoded a megabyte (whole items) at a time.
        let mut buf = vec![0u8; ((1 << 20) / itemsize).max(1) * itemsize];
        let mut read = 0u64;
        while read < nbytes {
            let want = buf.len().min((nbytes - read) as usize);
            let got = fill(&mut f, &mut buf[..want]).map_err(|e| entry_io(&entry, e))?;
            crc.update(&buf[..got]);
            read += got as u64;
            if got < want {
                return Err(bad(format!(
                    "truncated: {read} of the {nbytes} data bytes {} needs",
                    what()
                )));
            }
            header.decode_items(&buf[..got], &mut values).map_err(bad)?;
        }
        if fill(&mut f, &mut [0u8; 1]).map_err(|e| entry_io(&entry, e))? > 0 {
            return Err(bad(format!("holds more data than {} needs", what())));
        }
        if crc.finalize() != e.crc {
            return Err(bad("corrupt data (its CRC-32 does not match)".into()));
        }
        Ok(header.in_c_order(values))
    }
}

/// A Python literal of an `.npy` header.
#[derive(Clone, Debug, PartialEq)]
enum Lit {
    Str(String),
    Int(i128),
    Bool(bool),
    None,
    Seq(Vec<Lit>),
    Dict(Vec<(Lit, Lit)>),
}

/// A parser of the Python literals NumPy writes in `.npy` headers: a dict
/// of strings, integers, booleans, `None`, tuples and lists.
struct Literal<'a> {
    s: &'a [u8],
    at: usize,
}

impl Literal<'_> {
    fn space(&mut self) {
        while self.s.get(self.at).is_some_and(|b| b.is_ascii_whitespace()) {
            self.at += 1;
        }
    }

    fn eat(&mut self, b: u8) -> bool {
        self.space();
        if self.s.get(self.at) == Some(&b) {
            self.at += 1;
            true
        } else {
            false
        }
    }

    fn value(&mut self, depth: usize) -> Result<Lit, String> {
        if depth > 32 {
            return Err("nested too deep".into());
        }
        self.space();
        let c = *self.s.get(self.at).ok_or("ends early")?;
        match c {
            b'\'' | b'"' => {
                self.at += 1;
                let mut out = String::new();
                loop {
                    let b = *self.s.get(self.at).ok_or("an unterminated string")?;
                    self.at += 1;
                    match b {
                        _ if b == c => return Ok(Lit::Str(out)),
                        b'\\' => {
                            let e = *self.s.get(self.at).ok_or("an unterminated string")?;
                            self.at += 1;
                            out.push(match e {
                                b'n' => '\n',
                                b't' => '\t',
                                b'\\' | b'\'' | b'"' => e as char,
                                _ => return Err("an escape it does not read".into()),
                            });
                        }
                        _ => out.push(b as char),
                    }
                }
            }
            b'(' | b'[' => {
                let close = if c == b'(' { b')' } else { b']' };
                self.at += 1;
                let mut items = Vec::new();
                loop {
                    if self.eat(close) {
                        return Ok(Lit::Seq(items));
                    }
                    items.push(self.value(depth + 1)?);
                    if !self.eat(b',') {
                        if self.eat(close) {
                            return Ok(Lit::Seq(items));
                        }
                        return Err("a bad tuple or list".into());
                    }
                }
            }
            b'{' => {
                self.at += 1;
                let mut items = Vec::new();
                loop {
                    if self.eat(b'}') {
                        return Ok(Lit::Dict(items));
                    }
                    let k = self.value(depth + 1)?;
                    if !self.eat(b':') {
                        return Err("a dict entry without ':'".into());
                    }
                    let v = self.value(depth + 1)?;
                    items.push((k, v));
                    if !self.eat(b',') {
                        if self.eat(b'}') {
                            return Ok(Lit::Dict(items));
                        }
                        return Err("a bad dict".into());
                    }
                }
            }
            _ => {
                let start = self.at;
                while self
                    .s
                    .get(self.at)
                    .is_some_and(|b| b.is_ascii_alphanumeric() || matches!(b, b'-' | b'+' | b'_'))
                {
                    self.at += 1;
                }
                let word = std::str::from_utf8(&self.s[start..self.at]).unwrap_or("");
                match word {
                    "True" => Ok(Lit::Bool(true)),
                    "False" => Ok(Lit::Bool(false)),
                    "None" => Ok(Lit::None),
                    _ => word
                        .strip_suffix('L')
                        .unwrap_or(word)
                        .parse()
                        .map(Lit::Int)
                        .map_err(|_| format!("{word:?} is not a literal it reads")),
                }
            }
        }
    }
}

/// The dtype, shape and order of an `.npy` header's dict (the keys
/// `descr`, `fortran_order` and `shape`, and no other).
fn parse_header(text: &str) -> Result<(Dtype, Vec<u64>, bool), String> {
    let mut p = Literal {
        s: text.as_bytes(),
        at: 0,
    };
    let bad = |why: String| format!("bad .npy header ({why})");
    let lit = p.value(0).map_err(bad)?;
    p.space();
    if p.at != p.s.len() {
        return Err(bad("text after the header's dict".into()));
    }
    let Lit::Dict(items) = lit else {
        return Err(bad("not a dict".into()));
    };
    let mut descr = None;
    let mut fortran = None;
    let mut shape = None;
    for (k, v) in items {
        match k {
            Lit::Str(k) if k == "descr" => descr = Some(v),
            Lit::Str(k) if k == "fortran_order" => fortran = Some(v),
            Lit::Str(k) if k == "shape" => shape = Some(v),
            _ => return Err(bad("the keys are not descr, fortran_order and shape".into())),
        }
    }
    let (Some(descr), Some(fortran), Some(shape)) = (descr, fortran, shape) else {
        return Err(bad("the keys are not descr, fortran_order and shape".into()));
    };
    let dtype =
        match descr {
            Lit::Str(d) => Dtype::parse(&d)?,
            _ => return Err(
                "a structured dtype is not a plain number or string (object arrays are never read)"
                    .into(),
            ),
        };
    let Lit::Bool(fortran) = fortran else {
        return Err(bad("fortran_order is not True or False".into()));
    };
    let Lit::Seq(dims) = &shape else {
        return Err(format!("bad shape {shape:?}"));
    };
    let shape = dims
        .iter()
        .map(|d| match d {
            Lit::Int(n) => u64::try_from(*n).ok(),
            _ => None,
        })
        .collect::<Option<Vec<u64>>>()
        .ok_or_else(|| format!("bad shape {dims:?}"))?;
    Ok((dtype, shape, fortran))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::npz::{write_npz_to, Array};
    use std::io::{Cursor, Write};

    fn archive(arrays: &[Array]) -> Vec<u8> {
        let mut out = Vec::new();
        write_npz_to(&mut out, arrays).unwrap();
        out
    }

    #[test]
    fn what_the_writer_writes_reads_back() {
        let arrays = [
            Array::f64("x", vec![2, 3], vec![0.5, -1.0, 2.0, 3.0, 4.0, f64::MAX]),
            Array::i64("n", vec![], vec![-7]),
            Array::str("s", vec!["ab".into(), "é".into(), String::new()]),
        ];
        let mut npz = NpzArchive::new(Cursor::new(archive(&arrays))).unwrap();
        let names: Vec<_> = npz.entries().iter().map(|e| e.name.clone()).collect();
        assert_eq!(names, ["x.npy", "n.npy", "s.npy"]);
        for (i, a) in arrays.iter().enumerate() {
            let h = npz.header(i).unwrap();
            assert_eq!(
                h.shape,
                a.shape.iter().map(|&d| d as u64).collect::<Vec<_>>()
            );
            assert_eq!(h.dtype, Dtype::of(&a.data));
            assert_eq!(npz.values(i, &h).unwrap(), a.data);
        }
    }

    #[test]
    fn headers_numpy_writes_parse() {
        let (d, s, f) =
            parse_header("{'descr': '>i4', 'fortran_order': True, 'shape': (2, 3), }   \n")
                .unwrap();
        assert_eq!(
            (d.kind, d.itemsize, d.big_endian, s, f),
            ('i', 4, true, vec![2, 3], true)
        );
        let (d, s, _) =
            parse_header("{'shape': (), 'descr': '<U5', 'fortran_order': False}").unwrap();
        assert_eq!((d.kind, d.itemsize, s), ('U', 20, vec![]));
        for (text, needle) in [
            (
                "{'descr': '|O', 'fortran_order': False, 'shape': (1,)}",
                "object",
            ),
            (
                "{'descr': [('a', '<f8')], 'fortran_order': False, 'shape': (1,)}",
                "object",
            ),
            (
                "{'descr': '<f8', 'fortran_order': False, 'shape': (-1,)}",
                "bad shape",
            ),
            ("{'descr': '<f8', 'shape': (1,)}", "keys"),
            (
                "{'descr': '<f8', 'fortran_order': False, 'shape': (1,), 'x': 1}",
                "keys",
            ),
            (
                "{'descr': '<q9', 'fortran_order': False, 'shape': (1,)}",
                "not a dtype",
            ),
            (
                "{'descr': '<f8', 'fortran_order': 0, 'shape': (1,)}",
                "fortran_order",
            ),
            ("[1, 2]", "not a dict"),
            ("{'descr': '<f8'", "bad .npy header"),
        ] {
            let e = parse_header(text).unwrap_err();
            assert!(e.contains(needle), "{text}: {e}");
        }
    }

    #[test]
    fn narrow_big_endian_and_fortran_arrays_decode_to_c_order() {
        let h = |descr: &str, shape: Vec<u64>, fortran_order| NpyHeader {
            dtype: Dtype::parse(descr).unwrap(),
            shape,
            fortran_order,
            data_offset: 0,
        };
        let be: Vec<u8> = [-2i16, 300].iter().flat_map(|x| x.to_be_bytes()).collect();
        assert_eq!(
            h(">i2", vec![2], false).decode(&be).unwrap(),
            Data::I64(vec![-2, 300])
        );
        let f32s: Vec<u8> = [1.5f32, -0.25]
            .iter()
            .flat_map(|x| x.to_le_bytes())
            .collect();
        assert_eq!(
            h("<f4", vec![2], false).decode(&f32s).unwrap(),
            Data::F64(vec![1.5, -0.25])
        );
        // Column-major [[1, 2, 3], [4, 5, 6]].
        let f: Vec<u8> = [1i64, 4, 2, 5, 3, 6]
            .iter()
            .flat_map(|x| x.to_le_bytes())
            .collect();
        assert_eq!(
            h("<i8", vec![2, 3], true).decode(&f).unwrap(),
            Data::I64(vec![1, 2, 3, 4, 5, 6])
        );
        let bad: Vec<u8> = 0xD800u32.to_le_bytes().to_vec();
        assert!(h("<U1", vec![1], false)
            .decode(&bad)
            .unwrap_err()
            .contains("code point"));
        assert!(h("|b1", vec![1], false).decode(&[1]).is_err());
    }

    /// An archive of one entry, `data` deflated, its directory saying
    /// `size` uncompressed bytes.
    fn deflated(data: &[u8], size: u32) -> Vec<u8> {
        let mut z = flate2::write::DeflateEncoder::new(Vec::new(), flate2::Compression::fast());
        z.write_all(data).unwrap();
        let packed = z.finish().unwrap();
        let name = b"x.npy";
        let crc = crc32fast::hash(data);
        let mut out = Vec::new();
        let fixed = |out: &mut Vec<u8>| {
            out.extend_from_slice(&20u16.to_le_bytes());
            out.extend_from_slice(&0u16.to_le_bytes());
            out.extend_from_slice(&8u16.to_le_bytes());
            out.extend_from_slice(&[0; 4]);
            out.extend_from_slice(&crc.to_le_bytes());
            out.extend_from_slice(&(packed.len() as u32).to_le_bytes());
            out.extend_from_slice(&size.to_le_bytes());
            out.extend_from_slice(&(name.len() as u16).to_le_bytes());
            out.extend_from_slice(&0u16.to_le_bytes());
        };
        out.extend_from_slice(&0x0403_4b50u32.to_le_bytes());
        fixed(&mut out);
        out.extend_from_slice(name);
        out.extend_from_slice(&packed);
        let cd = out.len() as u32;
        out.extend_from_slice(&0x0201_4b50u32.to_le_bytes());
        out.extend_from_slice(&20u16.to_le_bytes());
        fixed(&mut out);
        out.extend_from_slice(&[0; 14]); // comment, disk, attributes, offset 0
        out.extend_from_slice(name);
        let cd_size = out.len() as u32 - cd;
        out.extend_from_slice(&0x0605_4b50u32.to_le_bytes());
        out.extend_from_slice(&[0, 0, 0, 0, 1, 0, 1, 0]);
        out.extend_from_slice(&cd_size.to_le_bytes());
        out.extend_from_slice(&cd.to_le_bytes());
        out.extend_from_slice(&0u16.to_le_bytes());
        out
    }

    #[test]
    fn deflated_entries_read_and_a_bomb_is_refused_without_inflating_it() {
        let a = Array::f64("x", vec![3], vec![1.0, 2.0, 3.0]);
        let npy = a.npy().unwrap();
        let mut npz = NpzArchive::new(Cursor::new(deflated(&npy, npy.len() as u32))).unwrap();
        let h = npz.header(0).unwrap();
        assert_eq!(npz.values(0, &h).unwrap(), a.data);
        // 64 MiB of zeros past the data: refused by the directory's size.
        let mut bomb = npy.clone();
        bomb.resize(npy.len() + (64 << 20), 0);
        let mut npz = NpzArchive::new(Cursor::new(deflated(&bomb, bomb.len() as u32))).unwrap();
        let h = npz.header(0).unwrap();
        let e = npz.values(0, &h).unwrap_err().to_string();
        assert!(e.contains("'x'") && e.contains("more data"), "{e}");
        // The directory lying too: inflating stops one byte past the data.
        let mut npz = NpzArchive::new(Cursor::new(deflated(&bomb, npy.len() as u32))).unwrap();
        let h = npz.header(0).unwrap();
        let e = npz.values(0, &h).unwrap_err().to_string();
        assert!(e.contains("more data"), "{e}");
        // A flipped data byte: the CRC-32.
        let mut bytes = archive(std::slice::from_ref(&a));
        let at = 30 + 5 + h.data_offset as usize + 3;
        bytes[at] ^= 1;
        let mut npz = NpzArchive::new(Cursor::new(bytes)).unwrap();
        let h = npz.header(0).unwrap();
        assert!(npz.values(0, &h).unwrap_err().to_string().contains("CRC"));
    }

    #[test]
    fn what_is_not_an_archive_says_so_and_no_cut_panics() {
        for bytes in [&b""[..], b"just some text\n", b"\x93NUMPY\x01\x00"] {
            let e = NpzArchive::new(Cursor::new(bytes.to_vec())).unwrap_err();
            assert!(matches!(e, NpzError::NotAnArchive(_)), "{e}");
        }
        let bytes = archive(&[
            Array::f64("x", vec![2], vec![1.0, 2.0]),
            Array::str("s", vec!["a".into()]),
        ]);
        for cut in 0..bytes.len() {
            if let Ok(mut npz) = NpzArchive::new(Cursor::new(bytes[..cut].to_vec())) {
                for i in 0..npz.entries().len() {
                    if let Ok(h) = npz.header(i) {
                        let _ = npz.values(i, &h);
                    }
                }
            }
        }
        for at in 0..bytes.len() {
            let mut b = bytes.clone();
            b[at] = b[at].wrapping_add(0x5b);
            if let Ok(mut npz) = NpzArchive::new(Cursor::new(b)) {
                for i in 0..npz.entries().len() {
                    if let Ok(h) = npz.header(i) {
                        let _ = npz.values(i, &h);
                    }
                }
            }
        }
    }
}
