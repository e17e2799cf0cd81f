//! # tensegrity-figures
//!
//! Every figure of the toolkit, built as a [`tensegrity_io::figure::Figure`] from library
//! calls: the thesis figures (the table [`FIGURES`] and its parallel driver
//! [`build_figures`]), the rolling figures ([`rolling`]: `fig_rolling`, the panels of a `roll`
//! run), Fig. 4.18 from the Michell mass table ([`michell::mass_table_figure`]), the T-bar
//! side and top views ([`tbar::side_and_top`]) and the work–precision figure of the
//! integrators ([`work_precision::figure`]).
//!
//! Figures are built, not written: a front end opens the figure's sink
//! ([`tensegrity_io::sink::FigureSink`]) before the work, so a bad path fails at once, and
//! finishes it with the figure, and writes the figure's data ([`Drawn::data`]) beside it.
//! The only files written here are the CSVs of the sweeps behind
//! Figs. 3.13 and 4.18, into the data directory a front end opened ([`Context::sweep`]).
//!
//! | module | what |
//! |---|---|
//! | [`catalog`] | [`FIGURES`]: number, description, thesis caption, what differs, builder of every thesis figure; [`FiguresRequest`] (`quick`, `only`, `png`, `threads`) |
//! | [`data`] | [`Drawn`]: a figure and its data table (written beside it as CSV); the tables of structure drawings |
//! | [`index`] | [`FigureIndex`]: the index of a `figures` run (JSON and Markdown) |
//! | [`chapter2`] | chapter 2: Fig. 2.2 |
//! | [`driver`] | [`build_figures`]: the chosen figures on worker threads, each handed to the front end as it is built; [`Context`] (sweeps, shared rolling runs, [`Warning`]s) |
//! | [`draw`] | structures drawn to scale in one style: views, bars and strings, colouring by force, supports, loads, labels |
//! | [`structures`] | the statics of a structure coloured by force with its reactions; mode shapes and mechanisms |
//! | [`wheels`] | chapter 3: Figs. 3.1, 3.2, 3.3, 3.8, 3.9, 3.10, 3.11, 3.13 |
//! | [`michell`] | chapter 4: Figs. 4.1–4.20 and the mass-table figure |
//! | [`tbar`] | chapter 5: Figs. 5.1–5.3 and the side and top views of any T-bar |
//! | [`page`] | the size and resolution of a run's figures checked against every chosen figure before any is computed |
//! | [`rolling`] | [`FigRollingRequest`] and [`fig_rolling`]; the panels of one rolling run |
//! | [`work_precision`] | error against wall time of every integrator |
//!
//! Libraries name their parameters, never command-line flags: a request field here is
//! `t_end`, `quick` or `only`, and the front end spells it its own way.
//!
//! ```
//! use tensegrity_figures::FIGURES;
//! let fig = FIGURES.iter().find(|f| f.number == "5.2").unwrap();
//! let ctx = tensegrity_figures::Context::new(true, std::env::temp_dir());
//! let drawn = fig.build(&ctx)?;
//! assert_eq!(drawn.figure.panels[0].title, "T-bar wheel, side");
//! assert_eq!(fig.file_name("svg"), "fig_5_2.svg");
//! assert!(drawn.data.header().contains(&"x [m]".to_string()));
//! # Ok::<(), tensegrity_figures::FigureError>(())
//! ```
#![warn(missing_docs)]

pub mod animation;
pub mod catalog;
pub mod chapter2;
mod context;
pub mod data;
pub mod draw;
pub mod driver;
pub mod error;
pub mod estimate;
pub mod index;
pub mod load_path;
pub mod michell;
pub mod page;
pub mod rolling;
pub mod structures;
pub mod sweep_plot;
pub mod tbar;
pub mod warning;
pub mod wheels;
pub mod work_precision;

pub use catalog::{FigureSpec, FiguresRequest, FIGURES};
pub use data::Drawn;
pub use driver::{build_figures, Built, Context, Warning};
pub use error::{FigureError, Result};
pub use index::{FigureIndex, IndexEntry};
pub use rolling::{fig_rolling, fig_rolling_within, roll_figure, FigRolling, FigRollingRequest};
