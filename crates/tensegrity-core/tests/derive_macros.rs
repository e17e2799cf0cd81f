//! The two derive macros of `tensegrity-derive` on the examples of its crate docs:
//! `#[derive(Columns)]` (a report's scalar columns, with units, nested, flattened and first-of-list
//! fields, and an internally tagged enum) and `#[derive(Params)]` (a request's parameters, with
//! kinds, units, rules, a flattened part and an explicit order). They run here, as tests of the
//! crate the macros implement the traits of, rather than as doc-tests of the proc-macro crate:
//! a proc-macro crate's tests are built for the build host, which compiled tensegrity-core
//! and its linear algebra a second time (without optimisation) in every test build.

// the examples' types exist to be derived on: some fields and variants are never read
#[allow(dead_code)]
mod columns {
    use serde::Serialize;
    use tensegrity_core::columns::{col, Columns};
    use tensegrity_derive::Columns;

    #[derive(Serialize, Columns)]
    #[serde(tag = "kind", rename_all = "lowercase")]
    enum Shape {
        Round {
            #[column(unit = "m")]
            radius: f64,
        },
        Square,
    }

    #[derive(Serialize, Columns)]
    struct Gap {
        tolerance: f64,
        ratio: Option<f64>,
    }

    #[derive(Serialize, Columns)]
    struct Report {
        nodes: usize,
        #[column(unit = "kg")]
        mass_kg: f64,
        #[serde(rename = "I1")]
        #[column(unit = "kg m^2")]
        i1: f64,
        forces: Vec<f64>,
        #[column(nested)]
        shape: Shape,
        #[column(nested, only = "ratio")]
        gap: Option<Gap>,
        #[serde(flatten)]
        more: Gap,
        #[column(first)]
        rows: Vec<Gap>,
        #[column(skip)]
        echo: f64,
        #[serde(skip)]
        work: f64,
    }

    #[test]
    fn the_columns_of_the_crate_docs_example() {
        assert_eq!(
            Report::columns(),
            [
                col("nodes", ""),
                col("mass_kg", "kg"),
                col("I1", "kg m^2"),
                col("shape.kind", ""),
                col("shape.radius", "m"),
                col("gap.ratio", ""),
                col("tolerance", ""),
                col("ratio", ""),
                col("rows.0.tolerance", ""),
                col("rows.0.ratio", ""),
            ]
        );
    }
}

#[allow(dead_code)]
mod params {
    use serde::{Deserialize, Serialize};
    use tensegrity_core::request::{Kind, Param, Params, Rule};
    use tensegrity_derive::Params;

    #[derive(Default, Serialize, Deserialize, Params)]
    #[serde(default)]
    struct Checks {
        #[param(flag, help = "Fail on an invalid result")]
        strict: bool,
    }

    const METHODS: &[&str] = &["fdm", "dr"];

    #[derive(Default, Serialize, Deserialize, Params)]
    #[serde(default)]
    #[params(order = "strict, t_end")]
    struct Run {
        #[param(number, unit = "s", help = "Simulated time", positive)]
        t_end: f64,
        #[serde(rename = "q")]
        #[param(count, help = "Complexity", rule = AtLeast(1.0))]
        complexity: usize,
        #[param(choice = ["rk4", "rk45"], help = "Integrator", optional)]
        integrator: Option<String>,
        #[param(choice = METHODS, help = "Method")]
        method: String,
        #[param(angle, help = "Slope", required)]
        incline: Option<f64>,
        #[serde(flatten)]
        checks: Checks,
    }

    #[test]
    fn the_params_of_the_crate_docs_example() {
        assert_eq!(
            Run::params(),
            [
                Param::flag("strict", "Fail on an invalid result"),
                Param::count("q", "Complexity").rule(Rule::AtLeast(1.0)),
                Param::choice("integrator", &["rk4", "rk45"], "Integrator").optional(),
                Param::choice("method", METHODS, "Method"),
                Param::angle("incline", "Slope").required(),
                Param::number("t_end", "s", "Simulated time").positive(),
            ]
        );
        assert_eq!(Run::params()[4].kind, Kind::Angle);
    }
}
