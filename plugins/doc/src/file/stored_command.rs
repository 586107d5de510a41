//! The stored form of the commands in a scene file's history.
//!
//! Each history step keeps the [`Command`] that made it (the history panel's
//! "adjust last operation" re-issues it). A file stores it as RON, inside the
//! step's `command: Some(…)`. That text is a promise to every file ever
//! written, so it is pinned: `plugins/doc/tests/corpus/commands-v<N>.ron`
//! holds the stored text of at least one example of every command variant
//! for format version `N`, and `tests/stored_commands.rs` fails when the
//! text of any of them changes or a variant is missing there.
//!
//! Files of format versions 1 and 2 store commands in the shape of
//! [`StoredV2`], which is today's [`Command`]: its serde names are the stored
//! names. Version 3 stores them the same way with one exception: an
//! `AddMesh` whose step made a mesh of the pool from exactly its positions
//! and polygons names that mesh instead of repeating them,
//! `AddMesh(name: "…", mesh: 3, parent: …, transform: …)` (a 1M-quad mesh
//! was stored twice before). [`to_text`] gives the full form, which version
//! 3 still writes when the mesh differs and reads everywhere. The in-memory
//! command may still evolve:
//!
//! - a new variant, or a Rust rename kept by `#[serde(rename = "…")]`, leaves
//!   every stored text as it was (the golden file gains the new variant with
//!   `HEDRA_BLESS=1`);
//! - a change of a stored shape (a renamed or split variant, a field with a
//!   new meaning) needs a new format version: freeze the old shape here as
//!   `StoredV<N>` (copies of the command types as the golden file of version
//!   `N` reads them), convert it to the new [`Command`] in
//!   [`parse_history`] and [`from_text`], and bless the golden file of the
//!   new version; the old golden file stays and must still read.

use super::StoredHistory;
use super::mesh_text::StoredMesh;
use crate::command::{Command, NodeRef};
use crate::kept::KeptMesh;
use crate::scene::NodeTransform;
use hedra_geom::{FaceId, HalfEdgeMesh, VertexId};
use ron::value::RawValue;
use serde::de::{self, EnumAccess, IntoDeserializer, VariantAccess, Visitor};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// The stored shape of a command in files of format versions 1 and 2.
pub type StoredV2 = Command;

/// Why a stored command could not be read.
#[derive(Debug, thiserror::Error)]
pub enum StoredCommandError {
    /// The file's format version is newer (or older) than any this build reads.
    #[error("format version {0} has no stored commands this build knows")]
    Version(u32),
    /// The stored text is not a command of that version (the RON error has the
    /// line and column inside the command text).
    #[error("{0}")]
    Parse(#[from] ron::error::SpannedError),
    /// An `AddMesh` that names a mesh of a file's pool: it reads only
    /// inside its file.
    #[error("AddMesh names mesh {0} of a file's pool; it reads only inside its file")]
    PooledMesh(usize),
}

/// The text a scene file stores for a command, exactly as it appears inside
/// a history step's `command: Some(…)`.
pub fn to_text(command: &Command) -> String {
    ron::ser::to_string_pretty(command, config()).expect("commands always serialise")
}

/// Reads the stored text of a command as format version `version` wrote it.
///
/// # Errors
/// [`StoredCommandError::Version`] for a version this build does not read,
/// [`StoredCommandError::Parse`] for text that is not such a command.
pub fn from_text(version: u32, text: &str) -> Result<Command, StoredCommandError> {
    match version {
        1 | 2 => Ok(ron::from_str::<StoredV2>(text)?),
        3 => match ron::from_str::<ReadCommand>(text)? {
            ReadCommand::Command(c) => Ok(c),
            ReadCommand::PooledAddMesh { mesh, .. } => Err(StoredCommandError::PooledMesh(mesh)),
        },
        _ => Err(StoredCommandError::Version(version)),
    }
}

/// The serialisation of a command inside a scene file: past the file's
/// indentation depth, so on one line (see `file::to_string`).
fn config() -> ron::ser::PrettyConfig {
    ron::ser::PrettyConfig::new()
        .depth_limit(0)
        .struct_names(false)
}

/// Parses the history part of a file of format version `version`, its
/// commands converted to today's [`Command`] except for the references into
/// the mesh pool, which [`ReadCommand::resolve`] follows once the pool is
/// read. Versions 1 and 2 store today's shape ([`StoredV2`]); version 3 adds
/// the pooled `AddMesh`.
pub(super) fn parse_history(
    version: u32,
    raw: &RawValue,
) -> Result<StoredHistory<ReadCommand, StoredMesh, KeptMesh>, ron::error::SpannedError> {
    debug_assert!((1..=super::FORMAT_VERSION).contains(&version));
    if version >= 3 {
        return raw.into_rust::<StoredHistory<ReadCommand, StoredMesh, KeptMesh>>();
    }
    let h = raw.into_rust::<StoredHistory<StoredV2, StoredMesh, KeptMesh>>()?;
    Ok(StoredHistory {
        meshes: h.meshes,
        corners: h.corners,
        kept: h.kept,
        done: h
            .done
            .into_iter()
            .map(|t| t.map_command(ReadCommand::Command))
            .collect(),
        undone: h
            .undone
            .into_iter()
            .map(|t| t.map_command(ReadCommand::Command))
            .collect(),
        dropped: h.dropped,
        next_serial: h.next_serial,
        max_steps: h.max_steps,
    })
}

/// A command as a history step stores it: in full, or (version 3) an
/// `AddMesh` naming the mesh of the pool it made.
pub(super) enum ReadCommand {
    /// Any command, every field written out.
    Command(Command),
    /// `AddMesh(name, mesh, parent, transform)`: the positions and polygons
    /// are those of pool mesh `mesh`.
    PooledAddMesh {
        name: String,
        mesh: usize,
        parent: Option<NodeRef>,
        transform: NodeTransform,
    },
}

impl ReadCommand {
    /// Today's command, its pooled mesh (if any) taken from `pool`; `None`
    /// when the pool has no such mesh.
    pub(super) fn resolve(self, pool: &[std::sync::Arc<HalfEdgeMesh>]) -> Option<Command> {
        match self {
            ReadCommand::Command(c) => Some(c),
            ReadCommand::PooledAddMesh {
                name,
                mesh,
                parent,
                transform,
            } => {
                let m = pool.get(mesh)?;
                let positions = (0..m.vertex_capacity() as u32)
                    .map(|v| m.position(VertexId(v)))
                    .collect();
                let polygons = (0..m.face_capacity() as u32)
                    .map(|f| m.face_vertices(FaceId(f)).map(|v| v.0).collect())
                    .collect();
                Some(Command::AddMesh {
                    name,
                    positions,
                    polygons,
                    parent,
                    transform,
                })
            }
        }
    }
}

/// True when `mesh` is exactly what `AddMesh` builds from these positions
/// and polygons (no element removed, ids in order), so the command can name
/// the mesh instead of repeating them.
pub(super) fn made_from(
    mesh: &HalfEdgeMesh,
    positions: &[glam::DVec3],
    polygons: &[Vec<u32>],
) -> bool {
    mesh.vertex_count() == positions.len()
        && mesh.vertex_capacity() == positions.len()
        && mesh.face_count() == polygons.len()
        && mesh.face_capacity() == polygons.len()
        && positions.iter().enumerate().all(|(v, p)| {
            mesh.position(VertexId(v as u32))
                .to_array()
                .map(f64::to_bits)
                == p.to_array().map(f64::to_bits)
        })
        && polygons.iter().enumerate().all(|(f, poly)| {
            mesh.face_vertices(FaceId(f as u32))
                .map(|v| v.0)
                .eq(poly.iter().copied())
        })
}

/// A command as version 3 writes it: [`ReadCommand`]'s two shapes.
pub(super) enum WriteCommand<'a> {
    /// In full, as [`to_text`] writes it.
    Command(&'a Command),
    /// An `AddMesh` naming pool mesh `mesh`.
    PooledAddMesh {
        /// The command (an `AddMesh`).
        command: &'a Command,
        /// Its mesh's index in the pool.
        mesh: usize,
    },
}

impl Serialize for WriteCommand<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeStructVariant;
        match self {
            WriteCommand::Command(c) => c.serialize(s),
            WriteCommand::PooledAddMesh {
                command:
                    Command::AddMesh {
                        name,
                        parent,
                        transform,
                        ..
                    },
                mesh,
            } => {
                let mut v = s.serialize_struct_variant("Command", 0, "AddMesh", 4)?;
                v.serialize_field("name", name)?;
                v.serialize_field("mesh", mesh)?;
                v.serialize_field("parent", parent)?;
                v.serialize_field("transform", transform)?;
                v.end()
            }
            WriteCommand::PooledAddMesh { command, .. } => command.serialize(s),
        }
    }
}

/// The fields of a stored `AddMesh` of version 3, either shape.
#[derive(Deserialize)]
struct StoredAddMesh {
    name: String,
    #[serde(default, deserialize_with = "super::mesh_text::present")]
    mesh: Option<usize>,
    #[serde(default, deserialize_with = "super::mesh_text::present")]
    positions: Option<Vec<glam::DVec3>>,
    #[serde(default, deserialize_with = "super::mesh_text::present")]
    polygons: Option<Vec<Vec<u32>>>,
    #[serde(default)]
    parent: Option<NodeRef>,
    #[serde(default)]
    transform: NodeTransform,
}

impl<'de> Deserialize<'de> for ReadCommand {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = ReadCommand;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a command")
            }
            fn visit_enum<A: EnumAccess<'de>>(self, data: A) -> Result<ReadCommand, A::Error> {
                let (name, variant) = data.variant_seed(Identifier)?;
                if name != "AddMesh" {
                    // Every other variant: today's command reads it.
                    return Command::deserialize(Replay { name, variant })
                        .map(ReadCommand::Command);
                }
                let m = StoredAddMesh::deserialize(StructVariant(variant))?;
                match (m.mesh, m.positions, m.polygons) {
                    (Some(mesh), None, None) => Ok(ReadCommand::PooledAddMesh {
                        name: m.name,
                        mesh,
                        parent: m.parent,
                        transform: m.transform,
                    }),
                    (None, Some(positions), Some(polygons)) => {
                        Ok(ReadCommand::Command(Command::AddMesh {
                            name: m.name,
                            positions,
                            polygons,
                            parent: m.parent,
                            transform: m.transform,
                        }))
                    }
                    _ => Err(de::Error::custom(
                        "AddMesh needs either `mesh` or `positions` and `polygons`",
                    )),
                }
            }
        }
        d.deserialize_enum("Command", COMMAND_VARIANTS, V)
    }
}

/// A variant name, read as an identifier (not a quoted string).
struct Identifier;

impl<'de> de::DeserializeSeed<'de> for Identifier {
    type Value = String;
    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<String, D::Error> {
        struct V;
        impl Visitor<'_> for V {
            type Value = String;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a command name")
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<String, E> {
                Ok(v.to_string())
            }
        }
        d.deserialize_identifier(V)
    }
}

/// The names `deserialize_enum` is told (RON does not use them to parse).
const COMMAND_VARIANTS: &[&str] = &["AddMesh"];

/// Hands an enum whose variant name was already read to a derived
/// `Deserialize` (today's [`Command`]).
struct Replay<A> {
    name: String,
    variant: A,
}

impl<'de, A: VariantAccess<'de>> Deserializer<'de> for Replay<A> {
    type Error = A::Error;
    fn deserialize_any<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, A::Error> {
        visitor.visit_enum(self)
    }
    serde::forward_to_deserialize_any! {
        bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string
        bytes byte_buf option unit unit_struct newtype_struct seq tuple
        tuple_struct map struct enum identifier ignored_any
    }
}

impl<'de, A: VariantAccess<'de>> EnumAccess<'de> for Replay<A> {
    type Error = A::Error;
    type Variant = A;
    fn variant_seed<S: de::DeserializeSeed<'de>>(self, seed: S) -> Result<(S::Value, A), A::Error> {
        let name: de::value::StringDeserializer<A::Error> = self.name.into_deserializer();
        Ok((seed.deserialize(name)?, self.variant))
    }
}

/// A struct variant's fields, for a derived struct `Deserialize`.
struct StructVariant<A>(A);

impl<'de, A: VariantAccess<'de>> Deserializer<'de> for StructVariant<A> {
    type Error = A::Error;
    fn deserialize_any<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, A::Error> {
        self.0.struct_variant(&[], visitor)
    }
    fn deserialize_struct<V: Visitor<'de>>(
        self,
        _: &'static str,
        fields: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, A::Error> {
        self.0.struct_variant(fields, visitor)
    }
    serde::forward_to_deserialize_any! {
        bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string
        bytes byte_buf option unit unit_struct newtype_struct seq tuple
        tuple_struct map enum identifier ignored_any
    }
}
