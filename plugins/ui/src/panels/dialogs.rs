//! Dialogs: unsaved changes, the path prompt, warnings.

use super::*;

pub(super) fn dialogs(
    ctx: &egui::Context,
    state: &mut UiState,
    model: &Model,
    writers: &mut Writers,
    events: &mut Vec<UiEvent>,
) {
    // Unsaved changes.
    if let Some(pending) = state.confirm.clone() {
        let what = match &pending {
            Pending::Quit => "quitting",
            Pending::New => "starting a new scene",
            _ => "opening another scene",
        };
        egui::Window::new("Unsaved changes")
            .collapsible(false)
            .resizable(false)
            .anchor(egui::Align2::CENTER_CENTER, [0.0, 0.0])
            .show(ctx, |ui| {
                ui.label(format!(
                    "Save changes to {} before {what}?",
                    model.state.display_name()
                ));
                ui.horizontal(|ui| {
                    if ui.button("Save").clicked() {
                        state.confirm = None;
                        state.after_save = Some(pending.clone());
                        match &model.state.path {
                            Some(p) => {
                                writers.requests.write(DocRequest::Save(p.clone()));
                            }
                            None => begin_path(state, FilePurpose::SaveAs, &model.state),
                        }
                    }
                    if ui.button("Don't Save").clicked() {
                        state.confirm = None;
                        run_pending(
                            pending.clone(),
                            state,
                            &model.state,
                            &mut writers.requests,
                            &mut writers.exit,
                        );
                    }
                    if ui.button("Cancel").clicked() {
                        state.confirm = None;
                    }
                });
            });
    }
    // Path prompt (always available; the native dialog may run beside it).
    if let Some(mut prompt) = state.path_prompt.take() {
        let mut keep = true;
        egui::Window::new(prompt.purpose.title()).collapsible(false).resizable(false).anchor(egui::Align2::CENTER_CENTER, [0.0, 0.0]).show(ctx, |ui| {
            if !state.dialog_backend {
                ui.colored_label(egui::Color32::from_rgb(255, 200, 80), "No file dialog is available here (no desktop portal or zenity). Type the path:");
            } else if state.dialog.is_some() {
                ui.label("A file dialog is open; you can also type the path here:");
            }
            let resp = ui.add(egui::TextEdit::singleline(&mut prompt.text).desired_width(420.0));
            // The field takes the keyboard as the prompt opens: what is
            // typed next is the path, not shortcuts.
            if !prompt.focused {
                resp.request_focus();
                prompt.focused = true;
            }
            let enter = resp.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
            if ui.input(|i| i.key_pressed(egui::Key::Escape)) {
                keep = false;
                state.after_save = None;
            }
            ui.horizontal(|ui| {
                let reading = matches!(prompt.purpose, FilePurpose::Open | FilePurpose::Import);
                let verb = match prompt.purpose {
                    FilePurpose::Open => "Open",
                    FilePurpose::Import => "Import",
                    FilePurpose::Export(_) => "Export",
                    FilePurpose::SaveAs => "Save",
                };
                let ok = ui.button(verb).clicked() || enter;
                if ok && !prompt.text.trim().is_empty() {
                    let path = std::path::PathBuf::from(prompt.text.trim());
                    if reading && !path.exists() {
                        events.push(UiEvent::Error(format!("{}: no such file", path.display())));
                    } else {
                        events.push(UiEvent::File(FileAction::UsePath(prompt.purpose, path)));
                        keep = false;
                    }
                }
                if state.dialog_backend && state.dialog.is_none() && ui.button("Browse…").clicked() {
                    state.dialog = Some(files::spawn_dialog(prompt.purpose, None));
                }
                if ui.button("Cancel").clicked() {
                    keep = false;
                    state.after_save = None;
                }
            });
        });
        if keep {
            state.path_prompt = Some(prompt);
        }
    }
    // Warnings that need acknowledging (damaged history, …).
    if !model.status.warnings.is_empty() {
        let mut ok = false;
        egui::Window::new("Warning")
            .collapsible(false)
            .resizable(false)
            .anchor(egui::Align2::CENTER_CENTER, [0.0, 0.0])
            .show(ctx, |ui| {
                for w in &model.status.warnings {
                    ui.label(w);
                }
                ok = ui.button("OK").clicked();
            });
        if ok {
            events.push(UiEvent::ClearWarnings);
        }
    }
}
