//! `hedra`: the modeling window, or a headless subcommand.

use clap::Parser;
use hedra::cli::{Cli, run};
use std::process::ExitCode;

/// mimalloc keeps freed memory for reuse where glibc's malloc hands large
/// blocks back to the kernel: refining a mesh to level 7 again (a slider
/// drag, a level change) then costs half as long, without page faults.
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        Some(sub) => match run(sub) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => {
                eprintln!("hedra: error: {}", e.0);
                ExitCode::FAILURE
            }
        },
        None => open_window(cli),
    }
}

/// No subcommand: the modeling window, opening `cli.file`.
#[cfg(feature = "gui")]
fn open_window(cli: Cli) -> ExitCode {
    if let Some(f) = &cli.file
        && !f.exists()
    {
        eprintln!("hedra: error: {}: no such file", f.display());
        return ExitCode::FAILURE;
    }
    let faces = match cli
        .select
        .as_deref()
        .map(ron::from_str::<hedra::doc::FaceSet>)
    {
        None => None,
        Some(Ok(f)) => Some(f),
        Some(Err(e)) => {
            eprintln!("hedra: error: --select: {e}");
            return ExitCode::FAILURE;
        }
    };
    let run = match cli.run.as_deref().map(|p| {
        hedra::doc::input::read_to_string(p)
            .map_err(|e| format!("{}: {e}", p.display()))
            .and_then(|t| hedra::doc::script::parse(&t, p).map_err(|e| e.to_string()))
    }) {
        None => Vec::new(),
        Some(Ok(commands)) => commands,
        Some(Err(e)) => {
            eprintln!("hedra: error: --run: {e}");
            return ExitCode::FAILURE;
        }
    };
    let edit = cli.edit.map(|n| (n, faces));
    let options = hedra::GuiOptions {
        file: cli.file,
        screenshot: cli.screenshot,
        frames: cli.frames,
        edit,
        run,
    };
    match hedra::gui_app(options).run() {
        bevy::app::AppExit::Success => ExitCode::SUCCESS,
        bevy::app::AppExit::Error(code) => ExitCode::from(code.get()),
    }
}

/// No subcommand in a build without the window: say how to use this one.
#[cfg(not(feature = "gui"))]
fn open_window(_cli: Cli) -> ExitCode {
    eprintln!(
        "hedra: error: this hedra was built without the window (--no-default-features); run a subcommand (hedra --help lists them)"
    );
    ExitCode::FAILURE
}
