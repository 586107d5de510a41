//! `docs/architecture.md` is true (issue 34, item 7): every system that
//! Hedra's plugins schedule and every resource of Hedra's crates is named
//! there. Read from the running app: its schedules after the first frames
//! and the resources in its world, so a system or resource added without a
//! line in the document fails this test with its name.

use crate::user::User;
use bevy::ecs::error::Result;
use bevy::ecs::schedule::Schedules;
use bevy::ecs::system::{IntoSystem, System};

/// The last path segment of a Rust path, without generic arguments:
/// `hedra_edit::mesh_mode::select_elements` → `select_elements`.
fn short_name(path: &str) -> &str {
    let path = path.split('<').next().unwrap_or(path);
    path.rsplit("::").next().unwrap_or(path)
}

/// Whether a Rust path names an item of Hedra's own crates (`hedra`,
/// `hedra_scene`, ...), not Bevy's, egui's or the standard library's.
fn is_hedras(path: &str) -> bool {
    path.split("::")
        .next()
        .is_some_and(|krate| krate == "hedra" || krate.starts_with("hedra_"))
}

/// The names of Hedra's systems in every initialised schedule of `user`'s
/// app, with their schedule: one entry per system.
fn scheduled_systems(user: &User) -> Vec<(String, String)> {
    let schedules = user.app.world().resource::<Schedules>();
    let mut found = Vec::new();
    for (label, schedule) in schedules.iter() {
        let Ok(systems) = schedule.systems() else {
            continue;
        };
        for (_, system) in systems {
            let name = system.name().to_string();
            // Closures and piped systems have no name a reader could use.
            if is_hedras(&name) && !name.contains("{{closure}}") && !name.contains(" ") {
                found.push((format!("{label:?}"), short_name(&name).to_string()));
            }
        }
    }
    found
}

/// The short type names of Hedra's resources in `user`'s world.
fn resources(user: &User) -> Vec<String> {
    user.app
        .world()
        .iter_resources()
        .map(|(info, _)| info.name().to_string())
        .filter(|name| is_hedras(name))
        .map(|name| short_name(&name).to_string())
        .collect()
}

#[test]
fn the_architecture_document_names_every_system_and_resource() {
    let document = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/architecture.md"),
    )
    .expect("docs/architecture.md is there");
    // Named as `name` or with its module, `mesh_mode::name`.
    let named = |name: &str| {
        document.contains(&format!("`{name}`")) || document.contains(&format!("::{name}`"))
    };
    let mut user = User::new();
    // A few more frames, so that schedules which run later (egui's pass,
    // `Last`) are initialised too.
    user.frames(3);
    let systems = scheduled_systems(&user);
    let resources = resources(&user);
    // The reading itself works: the app has dozens of each.
    assert!(
        systems.len() > 40,
        "{} systems found: {systems:?}",
        systems.len()
    );
    assert!(
        resources.len() > 15,
        "{} resources found: {resources:?}",
        resources.len()
    );
    let mut missing: Vec<String> = systems
        .iter()
        .filter(|(_, name)| !named(name))
        .map(|(schedule, name)| format!("system `{name}` ({schedule})"))
        .collect();
    missing.extend(
        resources
            .iter()
            .filter(|name| !named(name))
            .map(|name| format!("resource `{name}`")),
    );
    missing.sort();
    missing.dedup();
    assert!(
        missing.is_empty(),
        "docs/architecture.md does not name {} of the app's systems and resources:\n{}",
        missing.len(),
        missing.join("\n")
    );
}

/// The Hedra resources that `system` may write, by short name, once it is
/// initialised in `user`'s world.
fn resources_written<O: 'static, M>(
    user: &mut User,
    system: impl IntoSystem<(), O, M>,
) -> Vec<String> {
    let mut system = IntoSystem::into_system(system);
    let access = system.initialize(user.app.world_mut());
    let access = access.combined_access();
    let mut written: Vec<String> = user
        .app
        .world()
        .iter_resources()
        .filter(|(info, _)| is_hedras(info.name().as_ref()))
        .filter(|(info, _)| access.has_write(info.id()))
        .map(|(info, _)| short_name(info.name().as_ref()).to_string())
        .collect();
    written.sort();
    written
}

/// Issue 34, item 1: the panels read state and send messages; no panel
/// holds a `ResMut` of another crate's state (the settings of edit and the
/// viewport, the selection, the status line, the previews, the input gate).
#[test]
fn the_panels_write_only_the_ui_crates_own_state() {
    let mut user = User::new();
    user.frames(2);
    let own = |names: &[String]| {
        names
            .iter()
            .filter(|n| !["UiState", "Preferences", "Recovery"].contains(&n.as_str()))
            .cloned()
            .collect::<Vec<_>>()
    };
    // The reading sees a write of another crate's state where there is one.
    let status = resources_written::<(), _>(&mut user, hedra_scene::apply_status_requests);
    assert_eq!(status, vec!["StatusMessage".to_string()]);
    let draw_ui = resources_written::<Result, _>(&mut user, hedra_ui::draw_ui);
    assert!(
        draw_ui.contains(&"UiState".to_string()),
        "the reading works: draw_ui keeps its own state ({draw_ui:?})"
    );
    assert_eq!(
        own(&draw_ui),
        Vec::<String>::new(),
        "draw_ui writes {draw_ui:?}"
    );
    let recovery = resources_written::<Result, _>(&mut user, hedra_ui::recovery::recovery_window);
    assert_eq!(
        own(&recovery),
        Vec::<String>::new(),
        "recovery_window writes {recovery:?}"
    );
    let preferences =
        resources_written::<Result, _>(&mut user, hedra_ui::recovery::preferences_window);
    assert_eq!(
        own(&preferences),
        Vec::<String>::new(),
        "preferences_window writes {preferences:?}"
    );
}
