//! File ▸ Export and dropping a file on the window, as a person uses them:
//! the menu, the path prompt pre-filled beside the open scene, Enter; then
//! the written file dropped back onto the window.

use crate::user::User;
use bevy::prelude::*;
use hedra_doc::export::ExportFormat;

/// Opens `path` as File ▸ Open would and waits for its nodes.
fn open_scene(user: &mut User, path: std::path::PathBuf, nodes: usize) {
    user.app
        .world_mut()
        .write_message(hedra_scene::DocRequest::Open(path));
    for _ in 0..100 {
        user.frame();
        if user.doc().nodes().count() == nodes {
            break;
        }
    }
    assert_eq!(user.doc().nodes().count(), nodes, "{}", user.status());
}

/// The text of the open path prompt, if one is open.
fn prompt(user: &User) -> Option<String> {
    user.app
        .world()
        .resource::<hedra_ui::UiState>()
        .path_prompt
        .as_ref()
        .map(|p| p.text.clone())
}

/// Every format of File ▸ Export: its menu item opens the prompt with
/// `export.<ext>` beside the scene, Enter writes the file there, and the
/// status line says so. Dropping each written file on the window imports
/// its nodes as one undo step.
#[test]
fn file_export_writes_every_format_and_a_dropped_export_comes_back() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("shapes.hedra.ron");
    let sample = std::path::Path::new(
        &std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR"),
    )
    .join("assets/samples/shapes.hedra.ron");
    std::fs::copy(&sample, &scene).unwrap();
    let nodes = hedra_doc::file::load(&scene)
        .unwrap()
        .session
        .doc
        .nodes()
        .count();
    let mut user = User::new();
    open_scene(&mut user, scene, nodes);
    for format in ExportFormat::ALL {
        let written = dir
            .path()
            .join(format!("export.{}", format.extensions()[0]));
        user.click_on("File");
        let export = user.find("Export ⏵");
        user.move_to(export);
        user.frames(2);
        user.click_on(format.menu_label());
        assert_eq!(
            prompt(&user),
            Some(written.display().to_string()),
            "{format:?}: the prompt offers export.{} beside the scene",
            format.extensions()[0]
        );
        user.tap(KeyCode::Enter);
        user.frames(2);
        assert_eq!(prompt(&user), None, "{format:?}: Enter closes the prompt");
        assert!(
            user.status()
                .contains(&format!("Exported {}", written.display())),
            "{format:?}: {}",
            user.status()
        );
        let bytes = std::fs::read(&written).unwrap();
        assert!(bytes.len() > 100, "{format:?}: {} bytes", bytes.len());
        assert_eq!(
            hedra_doc::export::ExportFormat::of_path(&written),
            Some(format)
        );

        let (before, steps) = (user.doc().nodes().count(), user.undo_steps());
        user.drop_file(written.clone());
        assert!(
            user.doc().nodes().count() > before,
            "{format:?}: dropping {} imported nothing: {}",
            written.display(),
            user.status()
        );
        assert_eq!(user.undo_steps(), steps + 1, "{format:?}: one undo step");
        user.shortcut(&[KeyCode::ControlLeft], KeyCode::KeyZ);
        assert_eq!(user.doc().nodes().count(), before, "{format:?}: undone");
    }
}

/// Edit ▸ Preferences…, dragging "Undo steps kept" down: the new limit is
/// saved in the app's own configuration folder (a test's, here) and the
/// history follows it. Found by the monkey (issue 35): the windowless app
/// saved its preferences into the machine's real configuration folder, so
/// one test's limit of 7 undo steps reached every later run.
#[test]
fn preferences_are_saved_in_the_apps_own_folder() {
    let mut user = User::new();
    let file = user.config_dir().join("preferences.ron");
    assert!(!file.exists());
    user.click_on("Edit");
    user.click_on("Preferences…");
    user.frames(2);
    assert!(user.shows("Undo steps kept"), "{:?}", user.status());
    let field = user.find("500");
    user.drag(field, field - Vec2::new(60.0, 0.0), 6);
    let prefs = user.app.world().resource::<hedra_ui::Preferences>().clone();
    assert!(
        prefs.undo_steps < 500,
        "the drag changed nothing: {prefs:?}"
    );
    let saved = std::fs::read_to_string(&file)
        .unwrap_or_else(|e| panic!("{} was not written: {e}", file.display()));
    assert!(
        saved.contains(&format!("undo_steps: {}", prefs.undo_steps)),
        "{saved}"
    );
    user.frames(2);
    let history = &user
        .app
        .world()
        .resource::<hedra_scene::DocState>()
        .session
        .history;
    assert_eq!(history.max_steps, prefs.undo_steps);
}

/// File ▸ Open Sample opens the sample as a new untitled scene: Ctrl+S
/// then asks where to save (the path prompt opens) and the sample's file
/// stays as it was. Found by the monkey (issue 35): it opened the table
/// sample, pressed Ctrl+S and rewrote `assets/samples/table.hedra.ron`,
/// which the USD test reads.
#[test]
fn a_sample_opens_untitled_and_save_never_overwrites_it() {
    let mut user = User::new();
    let sample =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/samples/table.hedra.ron");
    let before = std::fs::read(&sample).unwrap();
    user.click_on("File");
    user.click_on("Open Sample ⏵");
    user.click_on("table.hedra.ron");
    for _ in 0..100 {
        user.frame();
        if user.doc().nodes().next().is_some() {
            break;
        }
    }
    assert!(user.doc().nodes().count() > 1, "{}", user.status());
    let state = user.app.world().resource::<hedra_scene::DocState>();
    assert_eq!(state.path, None, "the sample opened as itself");
    assert!(
        user.status().contains("as a new scene"),
        "{}",
        user.status()
    );
    user.shortcut(&[KeyCode::ControlLeft], KeyCode::KeyS);
    user.frames(2);
    let asked = prompt(&user).expect("Ctrl+S asks where to save");
    assert!(asked.ends_with("untitled.hedra.ron"), "{asked}");
    user.tap(KeyCode::Escape);
    assert_eq!(std::fs::read(&sample).unwrap(), before);
}
