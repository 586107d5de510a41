//! The Hedra application: the headless CLI and, with the `gui` feature (on
//! by default), the plugin group of the Bevy crates, the windowed app and a
//! windowless app for tests.

pub mod cli;
#[cfg(feature = "gui")]
mod gui;

#[cfg(feature = "gui")]
pub use gui::*;
pub use hedra_doc as doc;
pub use hedra_geom as geom;
