//! Headless subcommands: the same document code as the GUI, no window.
//!
//! Every error is one line on stderr and a non-zero exit code, and no output
//! file is written unless the whole command succeeded.

use clap::{Parser, Subcommand};
use hedra_doc::export::ExportShape;
use hedra_doc::file::{self, FileError};
use hedra_doc::report::SceneReport;
use hedra_doc::{Session, script};
use std::path::{Path, PathBuf};

/// Hedra: polygon, subdivision and NURBS modeling. Without a subcommand,
/// opens the modeling window (optionally on FILE).
#[derive(Parser, Debug)]
#[command(name = "hedra", version, args_conflicts_with_subcommands = true)]
pub struct Cli {
    /// A headless subcommand; without one, the window opens.
    #[command(subcommand)]
    pub command: Option<Sub>,
    /// A scene (.hedra.ron) to open in the window.
    pub file: Option<PathBuf>,
    /// Save a screenshot of the window to this PNG after `--frames` frames, then quit.
    #[arg(long)]
    pub screenshot: Option<PathBuf>,
    /// Frames to render before the screenshot.
    #[arg(long, default_value_t = 30)]
    pub frames: u32,
    /// Start in edit mode on this mesh node (by name).
    #[arg(long, value_name = "NODE")]
    pub edit: Option<String>,
    /// With --edit: select these faces, a face set as in scripts,
    /// e.g. "Facing(direction: (0.0, 1.0, 0.0), degrees: 10.0)".
    #[arg(long, value_name = "FACES", requires = "edit")]
    pub select: Option<String>,
    /// Apply the commands of this script (as `hedra run` reads them) after
    /// opening, each one an undo step of the session.
    #[arg(long, value_name = "SCRIPT")]
    pub run: Option<PathBuf>,
}

/// The headless subcommands (`hedra info`, `hedra run`, …).
#[derive(Subcommand, Debug)]
pub enum Sub {
    /// Print the scene's nodes and, for each mesh, its counts and invariants.
    Info {
        /// The scene (.hedra.ron) to read.
        file: PathBuf,
        /// One JSON object instead of text (schema: docs/info-json.md).
        #[arg(long)]
        json: bool,
        /// Also print each mesh's half-edge and winged-edge tables.
        #[arg(long)]
        topology: bool,
        /// Also convert each mesh with a Catmull-Clark modifier to NURBS
        /// (as Object ▸ Convert ▸ To NURBS would, at the default tolerance)
        /// and print the patches, how many are exact, and the largest
        /// distance and normal angle measured.
        #[arg(long)]
        to_nurbs: bool,
    },
    /// Print the exact point, derivatives, normal and curvature of a curve
    /// or surface node at a parameter (local space).
    Eval {
        /// The scene (.hedra.ron) to read.
        file: PathBuf,
        /// The node's name (or `#ID`).
        node: String,
        /// `U` for a curve, `U,V` for a surface.
        #[arg(long, allow_hyphen_values = true)]
        at: String,
        /// One JSON object instead of text.
        #[arg(long)]
        json: bool,
    },
    /// Apply a RON script of commands (docs/commands.md) and save the result with its history.
    Run {
        /// The script: a RON list of commands.
        script: PathBuf,
        /// Start from this scene instead of an empty one.
        #[arg(long)]
        input: Option<PathBuf>,
        /// Where to write the resulting scene (.hedra.ron).
        #[arg(short, long)]
        output: PathBuf,
    },
    /// Undo steps of a saved scene's history.
    Undo {
        /// The saved scene (.hedra.ron) whose history to step back.
        file: PathBuf,
        /// How many steps to undo (at least 1).
        #[arg(long, default_value_t = 1)]
        steps: usize,
        /// Where to write the resulting scene (.hedra.ron).
        #[arg(short, long)]
        output: PathBuf,
    },
    /// Redo steps of a saved scene's history.
    Redo {
        /// The saved scene (.hedra.ron) whose history to step forward.
        file: PathBuf,
        /// How many undone steps to redo (at least 1).
        #[arg(long, default_value_t = 1)]
        steps: usize,
        /// Where to write the resulting scene (.hedra.ron).
        #[arg(short, long)]
        output: PathBuf,
    },
    /// Import a file's nodes (OBJ with UVs and normals, binary or ASCII STL, glTF/GLB, USD with subdivision and NURBS, STEP B-spline curves and surfaces) into a new scene (or --input) and save it.
    Import {
        /// The file to import (.obj, .stl, .gltf, .glb, .usda, .usdc, .usdz, .usd, .step or .stp).
        file: PathBuf,
        /// Start from this scene instead of an empty one.
        #[arg(long)]
        input: Option<PathBuf>,
        /// Where to write the resulting scene (.hedra.ron).
        #[arg(short, long)]
        output: PathBuf,
        /// Repair meshes that are not manifold into editable meshes (faces
        /// dropped, fans split) instead of keeping them as in the file.
        #[arg(long)]
        repair: bool,
    },
    /// Write the scene in the format the output's extension names: .obj
    /// keeps n-gons, .stl is triangulated, .glb/.gltf keep the hierarchy
    /// (meshes with a subdivision modifier written smooth, at its export
    /// level); .usda keeps the hierarchy, subdivision cages with their
    /// creases live and NURBS exact; .step/.stp writes NURBS surfaces and
    /// curves for CAD. What a format could not hold is printed as notes.
    Export {
        /// The scene (.hedra.ron) to read.
        file: PathBuf,
        /// The file to write; its extension picks the format (.obj, .stl, .gltf, .glb, .usda, .step or .stp).
        #[arg(short, long)]
        output: PathBuf,
        /// Subdivide every mesh this many levels (0–10) instead.
        #[arg(long, conflicts_with = "cage")]
        subdivide: Option<u32>,
        /// Write the editable cages, ignoring subdivision modifiers.
        #[arg(long)]
        cage: bool,
        /// Write STL as text (ASCII) instead of binary.
        #[arg(long)]
        ascii: bool,
        /// Decimate modifiers write this ratio of their input's faces
        /// (0 < RATIO ≤ 1), a level of their progressive mesh, instead of
        /// their own target.
        #[arg(long, value_name = "RATIO")]
        lod: Option<f64>,
        /// How OBJ writes curves: `polylines` (`l`, every reader) or `nurbs`
        /// (exact free-form `cstype bspline`/`curv`/`parm` records).
        #[arg(long, value_enum, default_value = "polylines")]
        curves: ObjCurves,
        /// STEP's length unit, stated in the file: `m` (Hedra's units as
        /// they are) or `mm` (× 1000).
        #[arg(long, value_enum, default_value = "m")]
        step_units: StepUnitsArg,
        /// STEP: write visible meshes and CSG solids as faceted shells
        /// (otherwise STEP holds the NURBS surfaces and curves only).
        #[arg(long)]
        step_meshes: bool,
        /// STEP: write meshes with a Catmull-Clark modifier as their limit
        /// surface in NURBS patches (one closed solid for a closed cage),
        /// as Object ▸ Convert ▸ To NURBS makes them.
        #[arg(long)]
        step_subdivision_nurbs: bool,
    },
}

/// A CLI failure: the message printed after `hedra: error: `.
#[derive(Debug)]
pub struct CliError(pub String);

impl<E: std::fmt::Display> From<E> for CliError {
    fn from(e: E) -> Self {
        CliError(e.to_string())
    }
}

fn load(path: &Path) -> Result<Session, CliError> {
    let loaded = file::load(path)?;
    for w in &loaded.warnings {
        eprintln!("hedra: warning: {}: {w}", path.display());
    }
    Ok(loaded.session)
}

fn save(session: &mut Session, path: &Path) -> Result<(), FileError> {
    file::save(session, path)
}

/// Refuses an output that is one of the command's input files (before
/// anything is read).
fn refuse_overwrite(output: &Path, inputs: &[Option<&Path>]) -> Result<(), CliError> {
    hedra_doc::input::refuse_overwrite(output, inputs.iter().flatten().copied())?;
    Ok(())
}

/// Runs a headless subcommand.
///
/// # Errors
/// [`CliError`] with a one-line message.
pub fn run(sub: Sub) -> Result<(), CliError> {
    match sub {
        Sub::Eval {
            file,
            node,
            at,
            json,
        } => {
            let session = load(&file)?;
            let params = at
                .split(',')
                .map(|x| {
                    x.trim()
                        .parse::<f64>()
                        .map_err(|_| CliError(format!("--at {at}: '{x}' is not a number")))
                })
                .collect::<Result<Vec<f64>, _>>()?;
            let reference = match node.strip_prefix('#').and_then(|i| i.parse().ok()) {
                Some(id) => hedra_doc::NodeRef::Id(id),
                None => hedra_doc::NodeRef::Name(node.clone()),
            };
            let e = hedra_doc::eval::evaluate(&session.doc, &reference, &params)
                .map_err(|m| CliError(format!("{}: {m}", file.display())))?;
            if json {
                emit(&format!(
                    "{}\n",
                    serde_json::to_string_pretty(&e).expect("evaluations serialise")
                ))?;
            } else {
                emit(&e.to_text())?;
            }
        }
        Sub::Info {
            file,
            json,
            topology,
            to_nurbs,
        } => {
            let session = load(&file)?;
            let report = SceneReport::new(&session);
            if json {
                emit(&format!("{}\n", report.to_json()))?;
            } else {
                emit(&report.to_text())?;
            }
            if topology {
                for node in session.doc.nodes() {
                    if let Some(mesh) = node.content.mesh() {
                        emit(&format!("topology of #{} {}:\n", node.id.0, node.name))?;
                        emit(&hedra_geom::topology::tables(mesh))?;
                    }
                }
            }
            if to_nurbs {
                let catmull_clark = |m: &hedra_doc::MeshContent| {
                    m.subdivision.as_ref().is_some_and(|s| {
                        s.options.scheme == hedra_geom::subdivision::Scheme::CatmullClark
                    })
                };
                for node in session.doc.nodes() {
                    let hedra_doc::NodeContent::Mesh(m) = &node.content else {
                        continue;
                    };
                    if !catmull_clark(m) {
                        continue;
                    }
                    let line = match m
                        .limit_nurbs(hedra_doc::command::DEFAULT_NURBS_TOLERANCE, &node.name)
                    {
                        Ok(c) => hedra_doc::command::nurbs_conversion_summary(&c),
                        Err(e) => format!("not convertible: {e}"),
                    };
                    emit(&format!("to NURBS #{} {}: {line}\n", node.id.0, node.name))?;
                }
            }
        }
        Sub::Run {
            script: script_path,
            input,
            output,
        } => {
            refuse_overwrite(&output, &[Some(script_path.as_path()), input.as_deref()])?;
            let text = hedra_doc::input::read_to_string(&script_path)
                .map_err(|e| CliError(format!("{}: {e}", script_path.display())))?;
            let commands = script::parse(&text, &script_path)?;
            let mut session = match input {
                Some(p) => load(&p)?,
                None => Session::new(),
            };
            let applied = script::run(&mut session, &commands, &script_path)?;
            save(&mut session, &output)?;
            eprintln!(
                "hedra: applied {} command(s), wrote {}",
                applied.len(),
                output.display()
            );
        }
        Sub::Undo { steps: 0, .. } | Sub::Redo { steps: 0, .. } => {
            return Err(CliError("--steps must be at least 1".into()));
        }
        Sub::Undo {
            file,
            steps,
            output,
        } => {
            refuse_overwrite(&output, &[Some(file.as_path())])?;
            let mut session = load(&file)?;
            let available = session.history.done().len();
            if steps > available {
                return Err(CliError(format!(
                    "{}: only {available} step(s) can be undone, not {steps}",
                    file.display()
                )));
            }
            for _ in 0..steps {
                session.undo();
            }
            save(&mut session, &output)?;
        }
        Sub::Redo {
            file,
            steps,
            output,
        } => {
            refuse_overwrite(&output, &[Some(file.as_path())])?;
            let mut session = load(&file)?;
            let available = session.history.undone().len();
            if steps > available {
                return Err(CliError(format!(
                    "{}: only {available} step(s) can be redone, not {steps}",
                    file.display()
                )));
            }
            for _ in 0..steps {
                session.redo();
            }
            save(&mut session, &output)?;
        }
        Sub::Import {
            file,
            input,
            output,
            repair,
        } => {
            refuse_overwrite(&output, &[Some(file.as_path()), input.as_deref()])?;
            let non_manifold = if repair {
                hedra_doc::import::NonManifold::Repair
            } else {
                hedra_doc::import::NonManifold::Keep
            };
            let meshes = hedra_doc::import::import_file_with(&file, non_manifold)?;
            // A summary as the warning, then its details.
            for (i, note) in hedra_doc::import::describe_repairs(&meshes)
                .iter()
                .enumerate()
            {
                if i == 0 {
                    eprintln!("hedra: warning: {}: {note}", file.display());
                } else {
                    eprintln!("{note}");
                }
            }
            let mut session = match input {
                Some(p) => load(&p)?,
                None => Session::new(),
            };
            let name = file.file_name().map_or_else(
                || file.display().to_string(),
                |n| n.to_string_lossy().into_owned(),
            );
            let applied = session.import(&meshes, &format!("Import {name}"));
            save(&mut session, &output)?;
            eprintln!(
                "hedra: imported {} object(s), wrote {}",
                applied.created.len(),
                output.display()
            );
        }
        Sub::Export {
            file,
            output,
            subdivide,
            cage,
            ascii,
            lod,
            curves,
            step_units,
            step_meshes,
            step_subdivision_nurbs,
        } => {
            refuse_overwrite(&output, &[Some(file.as_path())])?;
            let mut session = load(&file)?;
            if let Some(ratio) = lod {
                hedra_doc::modifiers::set_decimate_ratio(&mut session, ratio)?;
            }
            let shape = match (subdivide, cage) {
                (Some(level), _) => ExportShape::Subdivided(level),
                (None, true) => ExportShape::Cage,
                (None, false) => ExportShape::Evaluated,
            };
            let options = hedra_doc::export::ExportOptions {
                shape,
                ascii_stl: ascii,
                curves: match curves {
                    ObjCurves::Polylines => hedra_doc::export::CurveExport::Polylines,
                    ObjCurves::Nurbs => hedra_doc::export::CurveExport::FreeForm,
                },
                step: hedra_doc::step::StepOptions {
                    units: match step_units {
                        StepUnitsArg::M => hedra_doc::step::StepUnits::Metres,
                        StepUnitsArg::Mm => hedra_doc::step::StepUnits::Millimetres,
                    },
                    meshes: step_meshes,
                    subdivision_as_nurbs: step_subdivision_nurbs,
                },
            };
            let notes = hedra_doc::export::export_to_path(&session.doc, &output, options)
                .map_err(|e| CliError(e.to_string()))?;
            for note in &notes {
                eprintln!("hedra: note: {}: {note}", output.display());
            }
        }
    }
    Ok(())
}

/// How `hedra export` writes curves into OBJ.
#[derive(Copy, Clone, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum ObjCurves {
    /// `l` polylines through points of each curve.
    Polylines,
    /// Free-form NURBS records (exact).
    Nurbs,
}

/// The length unit `hedra export --step-units` writes STEP in.
#[derive(Copy, Clone, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum StepUnitsArg {
    /// Metres: Hedra's numbers as they are.
    M,
    /// Millimetres: every length × 1000.
    Mm,
}

/// Writes a report to standard output. When the reader has gone away (`hedra
/// info --json | head -1`), the rest of the report is dropped quietly, as
/// other command-line tools do, instead of failing.
fn emit(text: &str) -> Result<(), CliError> {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        Ok(()) => Ok(()),
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        Err(e) => Err(CliError(format!("cannot write to standard output: {e}"))),
    }
}
