//! Menus as data, in the style of the keymap (`hedra_edit::bindings::table`):
//! each item is a row of a table (its label, its key from the keymap, when
//! it can be chosen, what it sends), and [`draw_menu`] draws any table. The
//! tables are in `menus.rs` (File, Edit, Object), `mesh_menu.rs` (Mesh) and
//! `add_menu.rs` (Add).

use super::*;
use hedra_edit::bindings::{Action, KeyMode};

/// What a menu row may look at: the document and the tool state, read only.
pub(super) struct MenuState<'a> {
    /// The document.
    pub doc: &'a Document,
    /// Its undo history (for Undo and Redo).
    pub history: &'a hedra_doc::History,
    /// The selected objects.
    pub selection: &'a Selection,
    /// Edit mode: the edited node and its element selection.
    pub mode: &'a EditMode,
    /// Control-point mode: the edited curve or surface and its selected points.
    pub shape_edit: &'a hedra_edit::ShapeEdit,
    /// The 3D cursor: where new objects go.
    pub cursor: DVec3,
    /// Spin's axis in the edited node's local space: the view axis through
    /// the 3D cursor (Blender's), when the view is known.
    pub spin_axis: Option<(DVec3, DVec3)>,
    /// The recent files (File ▸ Open Recent).
    pub recent: &'a [std::path::PathBuf],
    /// Where the sample scenes are (File ▸ Open Sample).
    pub samples: Option<&'a std::path::Path>,
}

impl<'a> MenuState<'a> {
    /// What the menus look at this frame; `view_direction` is the
    /// viewport's (world), Spin's axis.
    pub fn of(model: &'a Model, view_direction: Option<DVec3>) -> Self {
        let cursor = model.cursor.0;
        // Spin turns about the view axis through the 3D cursor (Blender),
        // both given to the command in the edited node's local space.
        let spin_axis = model.mode.node.zip(view_direction).map(|(node, d)| {
            let to_local = model.state.session.doc.world_matrix(node).inverse();
            (
                to_local.transform_point3(cursor),
                to_local.transform_vector3(d),
            )
        });
        MenuState {
            doc: &model.state.session.doc,
            history: &model.state.session.history,
            selection: &model.selection,
            mode: &model.mode,
            shape_edit: &model.shape_edit,
            cursor,
            spin_axis,
            recent: &model.prefs.recent,
            samples: model.samples.as_ref().map(|d| d.0.as_path()),
        }
    }
}

impl MenuState<'_> {
    /// The node edit mode edits, as a command's reference.
    pub fn edited(&self) -> NodeRef {
        NodeRef::from(self.mode.node.expect("the Mesh menu shows in edit mode"))
    }

    /// The selected faces, as a command's set.
    pub fn faces(&self) -> hedra_doc::FaceSet {
        hedra_doc::FaceSet::Ids(self.mode.selection.faces.iter().map(|f| f.0).collect())
    }

    /// The selected edges, as a command's set.
    pub fn edges(&self) -> hedra_doc::EdgeSet {
        hedra_doc::EdgeSet::Ids(self.mode.selection.edges.iter().map(|e| e.0).collect())
    }

    /// The selected vertices, as a command's set.
    pub fn vertices(&self) -> hedra_doc::VertexSet {
        hedra_doc::VertexSet::Ids(self.mode.selection.vertices.iter().map(|v| v.0).collect())
    }

    /// The selected objects, as command references.
    pub fn nodes(&self) -> Vec<NodeRef> {
        self.selection.refs()
    }

    /// The transform of a new object: at the 3D cursor.
    pub fn at_cursor(&self) -> NodeTransform {
        NodeTransform {
            translation: self.cursor,
            ..NodeTransform::IDENTITY
        }
    }
}

/// Whether a row can be chosen now: `Err` says why not (shown on hover).
pub(super) type When = fn(&MenuState<'_>) -> Result<(), &'static str>;

/// What a chosen row sends.
pub(super) type Choose = fn(&MenuState<'_>, &mut Vec<UiEvent>);

/// A row that can always be chosen.
pub(super) const ALWAYS: When = |_| Ok(());

/// One menu item.
pub(super) struct MenuItem {
    /// The text shown.
    pub label: &'static str,
    /// The keymap action whose keys are shown after the label, and the key
    /// mode they are looked up in (so a menu cannot show a key that does
    /// something else).
    pub key: Option<(KeyMode, Action)>,
    /// Shown when the pointer rests on the item ("" for none).
    pub hover: &'static str,
    /// When it can be chosen.
    pub when: When,
    /// What it sends when chosen.
    pub choose: Choose,
}

/// A row of a menu table.
pub(super) enum MenuRow {
    /// A dim heading over a group of items.
    Heading(&'static str),
    /// A line between groups.
    Separator,
    /// An item.
    Item(MenuItem),
    /// A submenu of its own rows, with the key of its action after the label.
    Submenu(&'static str, Option<(KeyMode, Action)>, &'static [MenuRow]),
    /// Items made from the document (one per recent file, per curve pair, …),
    /// drawn by code.
    Listed(fn(&mut egui::Ui, &MenuState<'_>, &mut Vec<UiEvent>)),
}

/// An item with no key and no hover text.
pub(super) const fn item(label: &'static str, when: When, choose: Choose) -> MenuRow {
    MenuRow::Item(MenuItem {
        label,
        key: None,
        hover: "",
        when,
        choose,
    })
}

/// An item with the keys of `action` in `mode`.
pub(super) const fn keyed_item(
    label: &'static str,
    mode: KeyMode,
    action: Action,
    when: When,
    choose: Choose,
) -> MenuRow {
    MenuRow::Item(MenuItem {
        label,
        key: Some((mode, action)),
        hover: "",
        when,
        choose,
    })
}

/// The same row with `hover` shown when the pointer rests on it.
pub(super) const fn with_hover(row: MenuRow, hover: &'static str) -> MenuRow {
    match row {
        MenuRow::Item(item) => MenuRow::Item(MenuItem { hover, ..item }),
        other => other,
    }
}

/// Starts the interactive tool of `action`, as its keys would (edit
/// applies it before the shortcut systems read the next frame's keys).
pub(super) fn start_tool(events: &mut Vec<UiEvent>, action: Action) {
    events.push(UiEvent::Edit(hedra_edit::EditRequest::Start(action)));
}

/// A label with its keys after a tab, or the label alone.
fn label_of(label: &str, key: Option<(KeyMode, Action)>) -> String {
    match key {
        Some((mode, action)) => keyed_in(mode, label, action),
        None => label.to_string(),
    }
}

/// Draws `rows`; a chosen item sends its events and closes the menu.
pub(super) fn draw_menu(
    ui: &mut egui::Ui,
    rows: &[MenuRow],
    state: &MenuState<'_>,
    events: &mut Vec<UiEvent>,
) {
    for row in rows {
        match row {
            MenuRow::Heading(text) => {
                ui.label(egui::RichText::new(*text).weak());
            }
            MenuRow::Separator => {
                ui.separator();
            }
            MenuRow::Item(item) => {
                let allowed = (item.when)(state);
                let mut response = ui.add_enabled(
                    allowed.is_ok(),
                    egui::Button::new(label_of(item.label, item.key)),
                );
                if !item.hover.is_empty() {
                    response = response.on_hover_text(item.hover);
                }
                if let Err(why) = allowed
                    && !why.is_empty()
                {
                    response = response.on_disabled_hover_text(why);
                }
                if response.clicked() {
                    (item.choose)(state, events);
                    ui.close();
                }
            }
            MenuRow::Submenu(label, key, rows) => {
                ui.menu_button(label_of(label, *key), |ui| {
                    draw_menu(ui, rows, state, events)
                });
            }
            MenuRow::Listed(draw) => draw(ui, state, events),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every table of the menus, by name.
    fn tables() -> Vec<(&'static str, &'static [MenuRow])> {
        vec![
            ("File", crate::panels::menus::FILE_MENU),
            ("File (Quit)", crate::panels::menus::QUIT_MENU),
            ("Edit", crate::panels::menus::EDIT_MENU),
            ("Object", crate::panels::menus::OBJECT_MENU),
            ("Mesh (object mode)", crate::panels::menus::OBJECT_MESH_MENU),
            ("Boolean", crate::panels::csg_menu::BOOLEAN_MENU),
            ("Mesh", crate::panels::mesh_menu::MESH_MENU),
            ("Add", crate::panels::add_menu::ADD_MENU_ROWS),
            ("Add ▸ Curve", crate::panels::add_menu::CURVE_ITEMS),
            ("Add ▸ Surface", crate::panels::add_menu::SURFACE_ITEMS),
            ("Curve", crate::panels::curve_menu::CURVE_MENU),
        ]
    }

    /// The items of `rows` and of their submenus.
    fn items<'a>(rows: &'a [MenuRow], out: &mut Vec<&'a MenuItem>) {
        for row in rows {
            match row {
                MenuRow::Item(item) => out.push(item),
                MenuRow::Submenu(_, _, rows) => items(rows, out),
                _ => {}
            }
        }
    }

    /// A menu shows the keys the keymap gives its action in that mode, so
    /// a keyed item whose action has no chord there would show none (or a
    /// key from another mode): every key a table names is bound.
    #[test]
    fn every_key_a_menu_shows_is_bound_in_its_mode() {
        let mut keyed = 0;
        for (table, rows) in tables() {
            let mut found = Vec::new();
            items(rows, &mut found);
            assert!(!found.is_empty(), "{table} has items");
            for item in found {
                if let Some((mode, action)) = item.key {
                    keyed += 1;
                    let chord = hedra_edit::bindings::chord_label(mode, action);
                    assert!(
                        !chord.is_empty(),
                        "{table} ▸ {}: {action:?} has no key in {mode:?}",
                        item.label
                    );
                }
            }
        }
        assert!(keyed > 25, "{keyed} keyed items");
    }

    /// Within one menu no two items share a label (a user could not tell
    /// them apart, and the input tests click items by label).
    #[test]
    fn labels_are_unique_within_a_menu() {
        for (table, rows) in tables() {
            let mut found = Vec::new();
            items(rows, &mut found);
            let mut labels: Vec<&str> = found.iter().map(|i| i.label).collect();
            labels.sort();
            let before = labels.len();
            labels.dedup();
            assert_eq!(labels.len(), before, "{table} repeats a label");
        }
    }
}
