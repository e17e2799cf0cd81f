//! Materials for sizing: density ρ, Young's modulus E and yield strength σ_Y.
//!
//! A small built-in table covers the materials used in the thesis and common tensegrity
//! practice; user materials (e.g. from a scene file) are added to a [`MaterialTable`] and
//! shadow the built-in ones of the same name.

use crate::error::{CoreError, ModelError, Result};
use std::collections::BTreeMap;

/// An isotropic, linear-elastic, perfectly plastic material.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    /// Density ρ in kg/m³.
    pub density: f64,
    /// Young's modulus E in Pa.
    pub youngs_modulus: f64,
    /// Yield strength σ_Y in Pa.
    pub yield_strength: f64,
}

impl Material {
    /// A material from its density (kg/m³), Young's modulus (Pa) and yield strength (Pa).
    ///
    /// ```
    /// use tensegrity_core::Material;
    /// let alu = Material::new(2700.0, 60e9, 110e6);
    /// assert_eq!(alu.density, 2700.0);
    /// ```
    pub fn new(density: f64, youngs_modulus: f64, yield_strength: f64) -> Self {
        Self {
            density,
            youngs_modulus,
            yield_strength,
        }
    }

    /// Checks that every constant is strictly positive and finite; `name` labels the error.
    pub fn validate(&self, name: &str) -> Result<()> {
        let item = format!("material \"{name}\"");
        for (field, value) in [
            ("density", self.density),
            ("youngs_modulus", self.youngs_modulus),
            ("yield_strength", self.yield_strength),
        ] {
            if !(value.is_finite() && value > 0.0) {
                return Err(ModelError::NonPositiveConstant {
                    item,
                    name: field,
                    value,
                }
                .into());
            }
        }
        Ok(())
    }
}

/// The built-in materials: `(name, density kg/m³, E Pa, σ_Y Pa)`.
///
/// `aluminium` is the benchmark alloy of the minimum-mass literature (σ_Y = 110 MPa, E = 60 GPa);
/// the others are typical handbook values.
pub const BUILTIN_MATERIALS: &[(&str, f64, f64, f64)] = &[
    ("aluminium", 2700.0, 60e9, 110e6),
    ("steel", 7862.0, 206e9, 690e6),
    ("titanium", 4430.0, 114e9, 880e6),
    ("carbon_fibre", 1600.0, 150e9, 1500e6),
    ("nylon", 1140.0, 2.7e9, 75e6),
    ("uhmwpe", 970.0, 110e9, 3000e6),
];

/// Named materials: the built-in table plus user additions.
#[derive(Debug, Clone, PartialEq)]
pub struct MaterialTable {
    materials: BTreeMap<String, Material>,
}

impl Default for MaterialTable {
    fn default() -> Self {
        let materials = BUILTIN_MATERIALS
            .iter()
            .map(|&(name, rho, e, sy)| (name.to_string(), Material::new(rho, e, sy)))
            .collect();
        Self { materials }
    }
}

impl MaterialTable {
    /// The built-in table.
    pub fn builtin() -> Self {
        Self::default()
    }

    /// Adds (or replaces) a user material after validating it.
    ///
    /// ```
    /// use tensegrity_core::{Material, MaterialTable};
    /// let mut table = MaterialTable::builtin();
    /// table.insert("alu", Material::new(2700.0, 60e9, 110e6)).unwrap();
    /// assert!(table.get("alu").is_some());
    /// assert!(table.insert("bad", Material::new(-1.0, 1.0, 1.0)).is_err());
    /// ```
    pub fn insert(&mut self, name: &str, material: Material) -> Result<()> {
        material.validate(name)?;
        self.materials.insert(name.to_string(), material);
        Ok(())
    }

    /// The material called `name`, if any.
    pub fn get(&self, name: &str) -> Option<&Material> {
        self.materials.get(name)
    }

    /// The material called `name`, or an [`ModelError::UnknownMaterial`](crate::error::ModelError::UnknownMaterial) naming `item`.
    pub fn lookup(&self, name: &str, item: &str) -> Result<&Material> {
        self.materials.get(name).ok_or_else(|| {
            CoreError::Model(ModelError::UnknownMaterial {
                item: item.to_string(),
                name: name.to_string(),
                known: self.names().join(", "),
            })
        })
    }

    /// The known names, sorted.
    pub fn names(&self) -> Vec<&str> {
        self.materials.keys().map(String::as_str).collect()
    }
}
