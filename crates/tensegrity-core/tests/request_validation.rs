//! `Request::validate` refuses NaN and infinities in every numeric field, naming the field:
//! its JSON form writes them as `null`, which the per-field rules would take for unset.

use serde::{Deserialize, Serialize};
use tensegrity_core::request::{check_description, Request};
use tensegrity_derive::Params;

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, Params)]
#[serde(default, deny_unknown_fields)]
struct Geometry {
    #[param(number, unit = "m", help = "Radius", positive)]
    radius: f64,
}

impl Default for Geometry {
    fn default() -> Self {
        Geometry { radius: 1.0 }
    }
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Params)]
#[serde(default, deny_unknown_fields)]
struct Run {
    #[param(number, unit = "s", help = "Simulated time", positive)]
    t_end: f64,
    #[param(number, unit = "N s/m", help = "Damping", optional)]
    damping: Option<f64>,
    #[param(numbers, help = "Sample points")]
    grid: Vec<f64>,
    #[param(count, help = "Sides")]
    sides: usize,
    #[serde(flatten)]
    geometry: Geometry,
}

impl Default for Run {
    fn default() -> Self {
        Run {
            t_end: 1.0,
            damping: None,
            grid: vec![0.5],
            sides: 8,
            geometry: Geometry::default(),
        }
    }
}

impl Request for Run {
    const NAME: &'static str = "run";
}

/// The field and the text of the error of `run`'s validation.
fn refused(run: Run) -> (String, String) {
    let e = run.validate().unwrap_err();
    (e.name.to_string(), e.to_string())
}

#[test]
fn the_description_matches_and_the_default_validates() {
    check_description::<Run>().unwrap();
    Run::default().validate().unwrap();
}

#[test]
fn nan_in_a_plain_field_is_refused_naming_it() {
    let (name, text) = refused(Run {
        t_end: f64::NAN,
        ..Run::default()
    });
    assert_eq!(name, "t_end");
    assert_eq!(text, "t_end = NaN: must be finite and positive");
}

#[test]
fn infinity_in_an_optional_a_list_or_a_flattened_field_is_refused_naming_it() {
    let optional = Run {
        damping: Some(f64::INFINITY),
        ..Run::default()
    };
    assert_eq!(refused(optional).0, "damping");
    let list = Run {
        grid: vec![0.5, f64::NEG_INFINITY],
        ..Run::default()
    };
    assert_eq!(refused(list).0, "grid");
    let flattened = Run {
        geometry: Geometry { radius: f64::NAN },
        ..Run::default()
    };
    assert_eq!(refused(flattened).0, "radius");
}

#[test]
fn finite_values_still_meet_their_rules() {
    let negative = Run {
        t_end: -1.0,
        ..Run::default()
    };
    assert_eq!(
        refused(negative).1,
        "t_end = -1: must be finite and positive"
    );
    let set = Run {
        damping: Some(2.0),
        grid: vec![0.1, 0.2],
        ..Run::default()
    };
    set.validate().unwrap();
}
