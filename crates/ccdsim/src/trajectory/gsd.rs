//! GSD trajectories in the HOOMD schema, as read by the `gsd` package (`gsd.hoomd.open`),
//! HOOMD-blue, freud and OVITO.
//!
//! The file layer is GSD 2: a 256-byte header, a list of chunk names, and an index of
//! `(frame, N, location, M, id, type)` entries pointing at raw little-endian arrays. The index
//! is allocated ahead and doubled (moved to the end of the file) when full, and every frame's
//! entries are written after its data and flushed, so a file cut off by a crash still opens
//! with every frame written before it.
//!
//! Per frame: `configuration/step` (the frame number), `particles/position`,
//! `particles/velocity`, `particles/image` and `log/time` (seconds, `f64`). In the first frame,
//! and again whenever they change: `configuration/dimensions`, `configuration/box`,
//! `particles/N`, `particles/diameter`, `particles/mass` and `log/particles/id` (HOOMD readers
//! take a chunk missing from a frame from frame 0). As the schema prescribes, the box is
//! centred on the origin (positions are shifted by half the box; a 2D box has `Lz = 0`) and
//! arrays are `f32`: about seven significant digits. Use extended XYZ for full precision.

use super::frame::Frame;
use std::io::{self, Seek, SeekFrom, Write};

const MAGIC: u64 = 0x65DF_65DF_65DF_65DF;
const HEADER_SIZE: u64 = 256;
const INDEX_ENTRY_SIZE: u64 = 32;
const NAME_BLOCK: u64 = 64;
const INITIAL_INDEX_ENTRIES: u64 = 128;
/// The two version words as the `gsd` package (5.x) writes them for the HOOMD schema.
const VERSION_WORDS: [u32; 2] = [0x0002_0000, 0x0002_0001];

/// Element types of the GSD file layer.
#[derive(Clone, Copy)]
#[repr(u8)]
enum ElementType {
    U8 = 1,
    U32 = 3,
    U64 = 4,
    I32 = 7,
    F32 = 9,
    F64 = 10,
}

/// Chunk names; a chunk's id is its place in this list.
const NAMES: [&str; 11] = [
    "configuration/step",
    "configuration/dimensions",
    "configuration/box",
    "particles/N",
    "particles/position",
    "particles/velocity",
    "particles/image",
    "particles/diameter",
    "particles/mass",
    "log/time",
    "log/particles/id",
];

/// The chunk of angular velocities (radians per second, `f64`, three per body), after
/// [`NAMES`] in files of runs that keep spins ([`GsdWriter::create_with_spins`]).
const ANGULAR_VELOCITY: &str = "log/particles/angular_velocity";

/// Id of a name in [`NAMES`].
fn id_of(name: &str) -> u16 {
    NAMES
        .iter()
        .position(|n| *n == name)
        .expect("a listed name") as u16
}

/// One index entry (frame, N, location, M, id, type).
#[derive(Clone, Copy)]
struct IndexEntry {
    frame: u64,
    n: u64,
    location: u64,
    m: u32,
    id: u16,
    kind: ElementType,
}

impl IndexEntry {
    fn bytes(&self) -> [u8; INDEX_ENTRY_SIZE as usize] {
        let mut b = [0u8; INDEX_ENTRY_SIZE as usize];
        b[0..8].copy_from_slice(&self.frame.to_le_bytes());
        b[8..16].copy_from_slice(&self.n.to_le_bytes());
        b[16..24].copy_from_slice(&self.location.to_le_bytes());
        b[24..28].copy_from_slice(&self.m.to_le_bytes());
        b[28..30].copy_from_slice(&self.id.to_le_bytes());
        b[30] = self.kind as u8;
        b
    }
}

/// A chunk of one frame before it is written.
struct Chunk {
    id: u16,
    kind: ElementType,
    n: u64,
    m: u32,
    data: Vec<u8>,
}

/// The per-run values written in frame 0 and again only when they change.
#[derive(PartialEq)]
struct Constants {
    dimensions: u8,
    cell: [f32; 6],
    diameters: Vec<f32>,
    masses: Vec<f32>,
    ids: Vec<u64>,
}

/// Writes frames to a GSD file (HOOMD schema); see the module docs.
pub struct GsdWriter<W: Write + Seek> {
    out: W,
    /// Where the next chunk's data goes: the end of the file.
    end: u64,
    index_location: u64,
    index_capacity: u64,
    /// Every index entry written, as bytes (32 per chunk): kept to move the index when it
    /// grows, since the writer cannot read its own output back.
    index: Vec<u8>,
    frames: u64,
    constants: Option<Constants>,
    /// Whether the file has the [`ANGULAR_VELOCITY`] chunk.
    spins: bool,
}

impl<W: Write + Seek> GsdWriter<W> {
    /// Starts a GSD file on `out` (written from its start), naming `application` (e.g.
    /// `"ccdsim 0.1.0"`, at most 63 bytes are kept) in the header.
    pub fn create(out: W, application: &str) -> io::Result<Self> {
        Self::start(out, application, false)
    }

    /// [`GsdWriter::create`] for a run that keeps spins: each frame also holds the bodies'
    /// angular velocities, `log/particles/angular_velocity` (`N × 3` `f64`, radians per
    /// second; a disc's about the third axis).
    pub fn create_with_spins(out: W, application: &str) -> io::Result<Self> {
        Self::start(out, application, true)
    }

    fn start(out: W, application: &str, spins: bool) -> io::Result<Self> {
        let extra: &[&str] = if spins { &[ANGULAR_VELOCITY] } else { &[] };
        let names: Vec<u8> = NAMES
            .iter()
            .chain(extra)
            .flat_map(|n| n.bytes().chain(std::iter::once(0)))
            .collect();
        // Whole 64-byte blocks with at least one spare NUL: an empty name ends the list.
        let name_blocks = names.len() as u64 / NAME_BLOCK + 1;
        let namelist_location = HEADER_SIZE;
        let index_location = namelist_location + name_blocks * NAME_BLOCK;
        let end = index_location + INITIAL_INDEX_ENTRIES * INDEX_ENTRY_SIZE;
        let mut w = GsdWriter {
            out,
            end,
            index_location,
            index_capacity: INITIAL_INDEX_ENTRIES,
            index: Vec::new(),
            frames: 0,
            constants: None,
            spins,
        };
        w.out.seek(SeekFrom::Start(0))?;
        w.write_header(application, namelist_location, name_blocks)?;
        let mut block = vec![0u8; (name_blocks * NAME_BLOCK) as usize];
        block[..names.len()].copy_from_slice(&names);
        w.out.write_all(&block)?;
        w.out
            .write_all(&vec![0u8; (w.index_capacity * INDEX_ENTRY_SIZE) as usize])?;
        w.out.flush()?;
        Ok(w)
    }

    /// Number of frames written.
    #[must_use]
    pub fn frames(&self) -> u64 {
        self.frames
    }

    /// Appends one frame; the file is complete (readable) when this returns.
    pub fn write<const D: usize>(&mut self, frame: &Frame<D>) -> io::Result<()> {
        let n = frame.len() as u64;
        let (shift, cell) = match frame.cell.origin_and_size() {
            Some((origin, size)) => {
                let mut shift = [0.0; 3];
                let mut cell = [0.0f32; 6];
                for d in 0..D {
                    shift[d] = origin[d] + 0.5 * size[d];
                    cell[d] = size[d] as f32;
                }
                (shift, cell)
            }
            None => ([0.0; 3], [0.0; 6]),
        };
        let constants = Constants {
            dimensions: D as u8,
            cell,
            diameters: frame.radii.iter().map(|r| (2.0 * r) as f32).collect(),
            masses: frame.masses.iter().map(|&m| m as f32).collect(),
            ids: frame.ids.clone(),
        };
        let mut chunks = vec![Chunk {
            id: id_of("configuration/step"),
            kind: ElementType::U64,
            n: 1,
            m: 1,
            data: self.frames.to_le_bytes().to_vec(),
        }];
        let changed = self.constants.as_ref() != Some(&constants);
        if changed {
            chunks.push(Chunk {
                id: id_of("configuration/dimensions"),
                kind: ElementType::U8,
                n: 1,
                m: 1,
                data: vec![constants.dimensions],
            });
            chunks.push(Chunk {
                id: id_of("configuration/box"),
                kind: ElementType::F32,
                n: 6,
                m: 1,
                data: f32_bytes(constants.cell.iter().copied()),
            });
            chunks.push(Chunk {
                id: id_of("particles/N"),
                kind: ElementType::U32,
                n: 1,
                m: 1,
                data: u32::try_from(n)
                    .map_err(|_| io::Error::other("GSD counts bodies in 32 bits"))?
                    .to_le_bytes()
                    .to_vec(),
            });
        }
        let triples = |v: &dyn Fn(usize, usize) -> f32| {
            f32_bytes((0..frame.len()).flat_map(|i| (0..3).map(move |a| v(i, a))))
        };
        chunks.push(Chunk {
            id: id_of("particles/position"),
            kind: ElementType::F32,
            n,
            m: 3,
            data: triples(&|i, a| {
                if a < D {
                    (frame.positions[i][a] - shift[a]) as f32
                } else {
                    0.0
                }
            }),
        });
        chunks.push(Chunk {
            id: id_of("particles/velocity"),
            kind: ElementType::F32,
            n,
            m: 3,
            data: triples(&|i, a| {
                if a < D {
                    frame.velocities[i][a] as f32
                } else {
                    0.0
                }
            }),
        });
        let mut images = Vec::with_capacity(frame.len() * 12);
        for k in &frame.images {
            for a in 0..3 {
                let k = if a < D { k[a] } else { 0 };
                let k = i32::try_from(k)
                    .map_err(|_| io::Error::other("a periodic image beyond GSD's 32 bits"))?;
                images.extend_from_slice(&k.to_le_bytes());
            }
        }
        chunks.push(Chunk {
            id: id_of("particles/image"),
            kind: ElementType::I32,
            n,
            m: 3,
            data: images,
        });
        if changed {
            chunks.push(Chunk {
                id: id_of("particles/diameter"),
                kind: ElementType::F32,
                n,
                m: 1,
                data: f32_bytes(constants.diameters.iter().copied()),
            });
            chunks.push(Chunk {
                id: id_of("particles/mass"),
                kind: ElementType::F32,
                n,
                m: 1,
                data: f32_bytes(constants.masses.iter().copied()),
            });
        }
        chunks.push(Chunk {
            id: id_of("log/time"),
            kind: ElementType::F64,
            n: 1,
            m: 1,
            data: frame.time.to_le_bytes().to_vec(),
        });
        if changed {
            chunks.push(Chunk {
                id: id_of("log/particles/id"),
                kind: ElementType::U64,
                n,
                m: 1,
                data: constants.ids.iter().flat_map(|i| i.to_le_bytes()).collect(),
            });
        }
        if let (true, Some(spins)) = (self.spins, &frame.spins) {
            chunks.push(Chunk {
                id: NAMES.len() as u16,
                kind: ElementType::F64,
                n,
                m: 3,
                data: spins
                    .iter()
                    .flat_map(|w| w.0)
                    .flat_map(f64::to_le_bytes)
                    .collect(),
            });
        }
        // Readers search a frame's entries by id.
        debug_assert!(chunks.windows(2).all(|w| w[0].id < w[1].id));
        self.append(&chunks)?;
        if changed {
            self.constants = Some(constants);
        }
        Ok(())
    }

    /// Flushes and returns the stream.
    pub fn finish(mut self) -> io::Result<W> {
        self.out.flush()?;
        Ok(self.out)
    }

    /// Writes the chunks' data, then their index entries (so the index never points at data
    /// not yet written), then flushes.
    fn append(&mut self, chunks: &[Chunk]) -> io::Result<()> {
        let used = self.index.len() as u64 / INDEX_ENTRY_SIZE;
        let needed = used + chunks.len() as u64;
        if needed > self.index_capacity {
            self.grow_index(needed.max(2 * self.index_capacity))?;
        }
        self.out.seek(SeekFrom::Start(self.end))?;
        let mut entries = Vec::with_capacity(chunks.len() * INDEX_ENTRY_SIZE as usize);
        for c in chunks {
            self.out.write_all(&c.data)?;
            let entry = IndexEntry {
                frame: self.frames,
                n: c.n,
                location: self.end,
                m: c.m,
                id: c.id,
                kind: c.kind,
            };
            entries.extend_from_slice(&entry.bytes());
            self.end += c.data.len() as u64;
        }
        self.out.seek(SeekFrom::Start(
            self.index_location + used * INDEX_ENTRY_SIZE,
        ))?;
        self.out.write_all(&entries)?;
        self.out.flush()?;
        self.index.extend_from_slice(&entries);
        self.frames += 1;
        Ok(())
    }

    /// Copies the index to a larger block at the end of the file and points the header at it.
    fn grow_index(&mut self, capacity: u64) -> io::Result<()> {
        let mut index = vec![0u8; (capacity * INDEX_ENTRY_SIZE) as usize];
        index[..self.index.len()].copy_from_slice(&self.index);
        let location = self.end;
        self.out.seek(SeekFrom::Start(location))?;
        self.out.write_all(&index)?;
        self.out.flush()?;
        self.index_location = location;
        self.index_capacity = capacity;
        self.end = location + capacity * INDEX_ENTRY_SIZE;
        // Only the two index words of the header change.
        self.out.seek(SeekFrom::Start(8))?;
        self.out.write_all(&location.to_le_bytes())?;
        self.out.write_all(&capacity.to_le_bytes())?;
        self.out.flush()
    }

    fn write_header(
        &mut self,
        application: &str,
        namelist_location: u64,
        name_blocks: u64,
    ) -> io::Result<()> {
        let mut h = [0u8; HEADER_SIZE as usize];
        h[0..8].copy_from_slice(&MAGIC.to_le_bytes());
        h[8..16].copy_from_slice(&self.index_location.to_le_bytes());
        h[16..24].copy_from_slice(&self.index_capacity.to_le_bytes());
        h[24..32].copy_from_slice(&namelist_location.to_le_bytes());
        h[32..40].copy_from_slice(&name_blocks.to_le_bytes());
        h[40..44].copy_from_slice(&VERSION_WORDS[0].to_le_bytes());
        h[44..48].copy_from_slice(&VERSION_WORDS[1].to_le_bytes());
        let app = application.as_bytes();
        let app = &app[..app.len().min(63)];
        h[48..48 + app.len()].copy_from_slice(app);
        h[112..117].copy_from_slice(b"hoomd");
        self.out.write_all(&h)
    }
}

fn f32_bytes(values: impl Iterator<Item = f32>) -> Vec<u8> {
    values.flat_map(f32::to_le_bytes).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Vector;
    use crate::trajectory::Cell;
    use std::io::Cursor;

    fn u64_at(b: &[u8], at: usize) -> u64 {
        u64::from_le_bytes(b[at..at + 8].try_into().unwrap())
    }

    fn frame(t: f64) -> Frame<3> {
        Frame {
            time: t,
            cell: Cell::Periodic(Vector([2.0, 4.0, 6.0])),
            ids: vec![3, 5],
            positions: vec![Vector([1.0, 2.0, 3.0]), Vector([0.0, 0.5, 5.5])],
            images: vec![[0, 1, -2], [4, 0, 0]],
            strain: 0.0,
            velocities: vec![Vector([1.0, 0.0, 0.0]), Vector([0.0, -1.0, 0.25])],
            radii: vec![0.5, 0.25],
            masses: vec![1.0, 1.5],
            spins: None,
        }
    }

    /// The (frame, id, location, byte length) of every valid index entry.
    fn index(bytes: &[u8]) -> Vec<(u64, u16, u64, u64)> {
        let location = u64_at(bytes, 8) as usize;
        let capacity = u64_at(bytes, 16) as usize;
        let size = |kind: u8| match kind {
            1 => 1,
            3 | 7 | 9 => 4,
            4 | 10 => 8,
            _ => panic!("type {kind}"),
        };
        (0..capacity)
            .map(|k| &bytes[location + 32 * k..location + 32 * (k + 1)])
            .take_while(|e| u64_at(e, 16) != 0)
            .map(|e| {
                let m = u32::from_le_bytes(e[24..28].try_into().unwrap()) as u64;
                let id = u16::from_le_bytes(e[28..30].try_into().unwrap());
                (
                    u64_at(e, 0),
                    id,
                    u64_at(e, 16),
                    u64_at(e, 8) * m * size(e[30]),
                )
            })
            .collect()
    }

    #[test]
    fn header_names_and_first_frame() {
        let mut w = GsdWriter::create(Cursor::new(Vec::new()), "ccdsim test").unwrap();
        w.write(&frame(0.5)).unwrap();
        let bytes = w.finish().unwrap().into_inner();
        assert_eq!(u64_at(&bytes, 0), MAGIC);
        assert_eq!(&bytes[48..59], b"ccdsim test");
        assert_eq!(&bytes[112..118], b"hoomd\0");
        let names_at = u64_at(&bytes, 24) as usize;
        let names: Vec<&str> = bytes[names_at..]
            .split(|&b| b == 0)
            .take_while(|s| !s.is_empty())
            .map(|s| std::str::from_utf8(s).unwrap())
            .collect();
        assert_eq!(names, NAMES);
        let entries = index(&bytes);
        let ids: Vec<u16> = entries.iter().map(|e| e.1).collect();
        assert_eq!(ids, (0..NAMES.len() as u16).collect::<Vec<_>>());
        // Positions are centred on the box: (1, 2, 3) − (1, 2, 3) = 0.
        let pos = entries[4];
        let first = f32::from_le_bytes(
            bytes[pos.2 as usize..pos.2 as usize + 4]
                .try_into()
                .unwrap(),
        );
        assert_eq!(first, 0.0);
        let time = entries[9];
        let t = f64::from_le_bytes(
            bytes[time.2 as usize..time.2 as usize + 8]
                .try_into()
                .unwrap(),
        );
        assert_eq!(t, 0.5);
    }

    #[test]
    fn the_index_grows_and_stays_sorted_and_in_bounds() {
        let mut w = GsdWriter::create(Cursor::new(Vec::new()), "ccdsim").unwrap();
        for k in 0..100 {
            w.write(&frame(k as f64)).unwrap();
        }
        assert_eq!(w.frames(), 100);
        let bytes = w.finish().unwrap().into_inner();
        let entries = index(&bytes);
        // Frame 0 has every chunk, the others the five that change.
        assert_eq!(entries.len(), NAMES.len() + 99 * 5);
        assert!(u64_at(&bytes, 16) > INITIAL_INDEX_ENTRIES);
        assert!(entries
            .windows(2)
            .all(|w| (w[0].0, w[0].1) < (w[1].0, w[1].1)));
        for (_, _, at, len) in &entries {
            assert!(at + len <= bytes.len() as u64);
        }
        assert_eq!(entries.last().unwrap().0, 99);
    }

    #[test]
    fn changed_radii_are_written_again() {
        let mut w = GsdWriter::create(Cursor::new(Vec::new()), "ccdsim").unwrap();
        w.write(&frame(0.0)).unwrap();
        let mut grown = frame(1.0);
        grown.radii[0] = 0.75;
        w.write(&grown).unwrap();
        let bytes = w.finish().unwrap().into_inner();
        let second: Vec<u16> = index(&bytes)
            .iter()
            .filter(|e| e.0 == 1)
            .map(|e| e.1)
            .collect();
        assert_eq!(second, (0..NAMES.len() as u16).collect::<Vec<_>>());
    }
}
