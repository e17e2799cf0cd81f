//! # tensegrity-derive
//!
//! `#[derive(Columns)]`: the scalar result columns of a report (what a sweep writes, one row
//! a case), declared once on the report's fields. It implements
//! `tensegrity_core::columns::Columns`: the report's scalar JSON keys in key (field) order,
//! nested keys as `outer.inner`, each with its unit.
//!
//! The rule, field by field (the name is the JSON key: `#[serde(rename = "…")]` honoured):
//!
//! - `#[serde(skip)]` / `#[serde(skip_serializing)]`: no column;
//! - `#[column(skip)]`: no column (a serialised value that is not a result: an input echo, a
//!   detail);
//! - `#[serde(flatten)]`: the field type's own `Columns`, without prefix;
//! - `#[column(nested)]`: the field type's own `Columns` (an `Option<T>` or `Box<T>` has
//!   `T`'s), prefixed `field.`;
//! - `#[column(first)]`: a list (`Vec<T>`, `[T; N]`, `&[T]`): the columns of its first
//!   element `T`, prefixed `field.0.`;
//! - `only = "a, b"` beside `nested`, `first` or `flatten`: only those columns of the field
//!   type (named as in its own list), in its order;
//! - a field whose type is a collection — `Vec`, `VecDeque`, a map or a set, an array, a
//!   slice, a tuple, or an `Option` / `Box` / reference of one — : no column;
//! - every other field: one scalar column, its unit from `#[column(unit = "kg")]` (`""`, no
//!   unit, by default). A struct field serialised as an object must say `nested` or `skip`.
//!
//! An internally tagged enum (`#[serde(tag = "kind")]`) has the tag's column, then the fields
//! of its struct variants by the same rule (a name shared by several variants once). Generic
//! types and other enums are refused.
//!
//! (This example and the one below run as tests of tensegrity-core,
//! `crates/tensegrity-core/tests/derive_macros.rs`: a proc-macro crate's own tests would be
//! built for the build host, compiling the workspace's numerics a second time.)
//!
//! ```ignore
//! use serde::Serialize;
//! use tensegrity_core::columns::{col, Columns};
//! use tensegrity_derive::Columns;
//!
//! #[derive(Serialize, Columns)]
//! #[serde(tag = "kind", rename_all = "lowercase")]
//! enum Shape {
//!     Round {
//!         #[column(unit = "m")]
//!         radius: f64,
//!     },
//!     Square,
//! }
//!
//! #[derive(Serialize, Columns)]
//! struct Gap {
//!     tolerance: f64,
//!     ratio: Option<f64>,
//! }
//!
//! #[derive(Serialize, Columns)]
//! struct Report {
//!     nodes: usize,
//!     #[column(unit = "kg")]
//!     mass_kg: f64,
//!     #[serde(rename = "I1")]
//!     #[column(unit = "kg m^2")]
//!     i1: f64,
//!     forces: Vec<f64>,
//!     #[column(nested)]
//!     shape: Shape,
//!     #[column(nested, only = "ratio")]
//!     gap: Option<Gap>,
//!     #[serde(flatten)]
//!     more: Gap,
//!     #[column(first)]
//!     rows: Vec<Gap>,
//!     #[column(skip)]
//!     echo: f64,
//!     #[serde(skip)]
//!     work: f64,
//! }
//!
//! assert_eq!(
//!     Report::columns(),
//!     [
//!         col("nodes", ""),
//!         col("mass_kg", "kg"),
//!         col("I1", "kg m^2"),
//!         col("shape.kind", ""),
//!         col("shape.radius", "m"),
//!         col("gap.ratio", ""),
//!         col("tolerance", ""),
//!         col("ratio", ""),
//!         col("rows.0.tolerance", ""),
//!         col("rows.0.ratio", ""),
//!     ]
//! );
//! ```
//!
//! `#[derive(Params)]`: the parameters of a request (one `tensegrity_core::request::Param` per
//! field: name, kind, unit, help, rule, optional / required), declared once on its fields. It
//! implements `tensegrity_core::request::Params`, the supertrait of `Request` that the command
//! line's flags, the sweep axes and the Python signatures, stubs and docstrings are built from.
//! Field by field, in field order (the name is the serde key: `#[serde(rename = "…")]`
//! honoured; `#[serde(skip)]` fields have none):
//!
//! - `#[param(<kind>, help = …)]`, the kind one of `number`, `count`, `angle` (unit `rad`),
//!   `flag`, `text`, `counts`, `numbers`, or `choice = ["a", "b"]` / `choice = Type::NAMES` (a
//!   const `&[&str]`); `help` a string or a const path;
//! - `unit = "N"`; a rule: `positive`, `non_negative` or `rule = AtLeast(1.0)` (a
//!   `tensegrity_core::request::Rule`, its variants in scope); `optional` (may be `null`),
//!   `required` (no default, must be given);
//! - `#[serde(flatten)]` or `#[param(flatten)]` (a part serialised flat by other means): the
//!   field type's own `Params`, spliced in;
//! - `#[params(order = "a, b, …")]` on the struct: those parameters in that order, in the
//!   places they take together (a request that lists a flattened part's fields among its own).
//!
//! A field without `#[param]` (not flattened, not skipped) is refused at compile time.
//!
//! ```ignore
//! use serde::{Deserialize, Serialize};
//! use tensegrity_core::request::{Kind, Param, Params, Rule};
//! use tensegrity_derive::Params;
//!
//! #[derive(Default, Serialize, Deserialize, Params)]
//! #[serde(default)]
//! struct Checks {
//!     #[param(flag, help = "Fail on an invalid result")]
//!     strict: bool,
//! }
//!
//! const METHODS: &[&str] = &["fdm", "dr"];
//!
//! #[derive(Default, Serialize, Deserialize, Params)]
//! #[serde(default)]
//! #[params(order = "strict, t_end")]
//! struct Run {
//!     #[param(number, unit = "s", help = "Simulated time", positive)]
//!     t_end: f64,
//!     #[serde(rename = "q")]
//!     #[param(count, help = "Complexity", rule = AtLeast(1.0))]
//!     complexity: usize,
//!     #[param(choice = ["rk4", "rk45"], help = "Integrator", optional)]
//!     integrator: Option<String>,
//!     #[param(choice = METHODS, help = "Method")]
//!     method: String,
//!     #[param(angle, help = "Slope", required)]
//!     incline: Option<f64>,
//!     #[serde(flatten)]
//!     checks: Checks,
//! }
//!
//! assert_eq!(
//!     Run::params(),
//!     [
//!         Param::flag("strict", "Fail on an invalid result"),
//!         Param::count("q", "Complexity").rule(Rule::AtLeast(1.0)),
//!         Param::choice("integrator", &["rk4", "rk45"], "Integrator").optional(),
//!         Param::choice("method", METHODS, "Method"),
//!         Param::angle("incline", "Slope").required(),
//!         Param::number("t_end", "s", "Simulated time").positive(),
//!     ]
//! );
//! assert_eq!(Run::params()[4].kind, Kind::Angle);
//! ```
#![warn(missing_docs)]

mod params;

use proc_macro::TokenStream;
use proc_macro2::TokenStream as Tokens;
use quote::quote;
use syn::meta::ParseNestedMeta;
use syn::{parse_macro_input, Attribute, Data, DeriveInput, Error, Fields, LitStr, Type};

/// Derives `tensegrity_core::columns::Columns` (the crate docs give the rule and the
/// attributes).
#[proc_macro_derive(Columns, attributes(column))]
pub fn derive_columns(input: TokenStream) -> TokenStream {
    let input = parse_macro_input!(input as DeriveInput);
    expand(&input)
        .unwrap_or_else(Error::into_compile_error)
        .into()
}

/// Derives `tensegrity_core::request::Params` (the crate docs give the rule and the
/// attributes).
#[proc_macro_derive(Params, attributes(param, params))]
pub fn derive_params(input: TokenStream) -> TokenStream {
    let input = parse_macro_input!(input as DeriveInput);
    params::expand(&input)
        .unwrap_or_else(Error::into_compile_error)
        .into()
}

fn expand(input: &DeriveInput) -> syn::Result<Tokens> {
    if !input.generics.params.is_empty() {
        return Err(Error::new_spanned(
            &input.generics,
            "#[derive(Columns)] takes no generic type",
        ));
    }
    let container = serde_attrs(&input.attrs)?;
    let no_rename_all = |s: &Serde, at: &dyn quote::ToTokens| match s.rename_all {
        true => Err(Error::new_spanned(
            at,
            "#[derive(Columns)] does not follow rename_all on fields",
        )),
        false => Ok(()),
    };
    let body = match &input.data {
        Data::Struct(s) => {
            no_rename_all(&container, &input.ident)?;
            fields(&s.fields)?
        }
        Data::Enum(e) => {
            let tag = container.tag.ok_or_else(|| {
                Error::new_spanned(
                    &input.ident,
                    "#[derive(Columns)] on an enum needs #[serde(tag = \"…\")]",
                )
            })?;
            let mut parts = vec![quote! { c.push(::tensegrity_core::columns::col(#tag, "")); }];
            for v in &e.variants {
                let variant = serde_attrs(&v.attrs)?;
                no_rename_all(&variant, v)?;
                if !variant.skip {
                    parts.push(fields(&v.fields)?);
                }
            }
            quote! { #(#parts)* let c = ::tensegrity_core::columns::dedup(c); }
        }
        Data::Union(u) => {
            return Err(Error::new_spanned(
                u.union_token,
                "#[derive(Columns)] takes no union",
            ))
        }
    };
    let name = &input.ident;
    Ok(quote! {
        impl ::tensegrity_core::columns::Columns for #name {
            fn columns() -> &'static [::tensegrity_core::columns::Column] {
                static COLUMNS: ::std::sync::OnceLock<
                    ::std::vec::Vec<::tensegrity_core::columns::Column>,
                > = ::std::sync::OnceLock::new();
                COLUMNS.get_or_init(|| {
                    #[allow(unused_mut)]
                    let mut c = ::std::vec::Vec::new();
                    #body
                    c
                })
            }
        }
    })
}

/// The statements that push the columns of these fields onto `c`.
fn fields(fields: &Fields) -> syn::Result<Tokens> {
    let Fields::Named(named) = fields else {
        return match fields {
            Fields::Unit => Ok(Tokens::new()),
            _ => Err(Error::new_spanned(
                fields,
                "#[derive(Columns)] takes named fields only",
            )),
        };
    };
    let mut out = Tokens::new();
    for f in &named.named {
        let serde = serde_attrs(&f.attrs)?;
        let column = column_attrs(&f.attrs)?;
        let ident = f.ident.as_ref().expect("named field");
        let name = serde
            .rename
            .unwrap_or_else(|| ident.to_string().trim_start_matches("r#").to_string());
        if serde.skip || column.skip {
            continue;
        }
        let only = &column.only;
        let ty = &f.ty;
        let group = |prefix: String, ty: &Type| {
            quote! {
                c.extend(::tensegrity_core::columns::nested(
                    #prefix,
                    <#ty as ::tensegrity_core::columns::Columns>::columns(),
                    &[#(#only),*],
                ));
            }
        };
        let kinds = [serde.flatten, column.nested, column.first];
        if kinds.iter().filter(|k| **k).count() > 1 {
            return Err(Error::new_spanned(
                f,
                "at most one of flatten, nested, first",
            ));
        }
        if !kinds.contains(&true) && !only.is_empty() {
            return Err(Error::new_spanned(
                f,
                "`only` goes with flatten, nested or first",
            ));
        }
        if kinds.contains(&true) && column.unit.is_some() {
            return Err(Error::new_spanned(f, "a unit goes on a scalar field"));
        }
        if serde.flatten {
            out.extend(group(String::new(), ty));
        } else if column.nested {
            out.extend(group(name, ty));
        } else if column.first {
            let element = element(ty).ok_or_else(|| {
                Error::new_spanned(ty, "`first` goes on a Vec, an array or a slice")
            })?;
            out.extend(group(format!("{name}.0"), element));
        } else if !is_collection(ty) {
            let unit = column.unit.unwrap_or_default();
            out.extend(quote! { c.push(::tensegrity_core::columns::col(#name, #unit)); });
        } else if column.unit.is_some() {
            return Err(Error::new_spanned(f, "a collection is not a scalar column"));
        }
    }
    Ok(out)
}

/// The last segment of a path type and its first type argument.
fn last_segment(ty: &Type) -> Option<(String, Option<&Type>)> {
    let Type::Path(p) = ty else { return None };
    let seg = p.path.segments.last()?;
    let arg = match &seg.arguments {
        syn::PathArguments::AngleBracketed(a) => a.args.iter().find_map(|a| match a {
            syn::GenericArgument::Type(t) => Some(t),
            _ => None,
        }),
        _ => None,
    };
    Some((seg.ident.to_string(), arg))
}

/// Whether the type serialises as a list or a map (also inside an `Option`, `Box` or
/// reference).
fn is_collection(ty: &Type) -> bool {
    match ty {
        Type::Array(_) | Type::Slice(_) => true,
        Type::Tuple(t) => !t.elems.is_empty(),
        Type::Reference(r) => is_collection(&r.elem),
        Type::Group(g) => is_collection(&g.elem),
        Type::Paren(p) => is_collection(&p.elem),
        _ => match last_segment(ty) {
            Some((name, arg)) => match name.as_str() {
                "Vec" | "VecDeque" | "HashMap" | "BTreeMap" | "HashSet" | "BTreeSet" => true,
                "Option" | "Box" => arg.is_some_and(is_collection),
                _ => false,
            },
            None => false,
        },
    }
}

/// The element type of a `Vec<T>`, `[T; N]` or `&[T]`.
fn element(ty: &Type) -> Option<&Type> {
    match ty {
        Type::Array(a) => Some(&a.elem),
        Type::Slice(s) => Some(&s.elem),
        Type::Reference(r) => element(&r.elem),
        _ => match last_segment(ty)? {
            (name, arg) if name == "Vec" => arg,
            _ => None,
        },
    }
}

/// What the serde attributes say about the columns.
#[derive(Default)]
pub(crate) struct Serde {
    rename: Option<String>,
    skip: bool,
    flatten: bool,
    tag: Option<String>,
    /// `rename_all`: refused on a struct or a variant (it renames fields); an enum's renames
    /// its variants, the values of the tag column.
    rename_all: bool,
}

pub(crate) fn serde_attrs(attrs: &[Attribute]) -> syn::Result<Serde> {
    let mut s = Serde::default();
    for attr in attrs.iter().filter(|a| a.path().is_ident("serde")) {
        attr.parse_nested_meta(|meta| {
            if meta.path.is_ident("rename") {
                if meta.input.peek(syn::Token![=]) {
                    s.rename = Some(meta.value()?.parse::<LitStr>()?.value());
                } else {
                    meta.parse_nested_meta(|m| {
                        if m.path.is_ident("serialize") {
                            s.rename = Some(m.value()?.parse::<LitStr>()?.value());
                            Ok(())
                        } else {
                            ignore(&m)
                        }
                    })?;
                }
            } else if meta.path.is_ident("skip") || meta.path.is_ident("skip_serializing") {
                s.skip = true;
            } else if meta.path.is_ident("flatten") {
                s.flatten = true;
            } else if meta.path.is_ident("tag") {
                s.tag = Some(meta.value()?.parse::<LitStr>()?.value());
            } else if meta.path.is_ident("rename_all") {
                s.rename_all = true;
                ignore(&meta)?;
            } else {
                ignore(&meta)?;
            }
            Ok(())
        })?;
    }
    Ok(s)
}

/// Consumes a serde argument the columns do not depend on.
fn ignore(meta: &ParseNestedMeta) -> syn::Result<()> {
    if meta.input.peek(syn::Token![=]) {
        meta.value()?.parse::<syn::Lit>()?;
    } else if meta.input.peek(syn::token::Paren) {
        meta.parse_nested_meta(|m| ignore(&m))?;
    }
    Ok(())
}

/// What the `#[column(…)]` attributes say.
#[derive(Default)]
struct Column {
    unit: Option<String>,
    skip: bool,
    nested: bool,
    first: bool,
    only: Vec<String>,
}

fn column_attrs(attrs: &[Attribute]) -> syn::Result<Column> {
    let mut c = Column::default();
    for attr in attrs.iter().filter(|a| a.path().is_ident("column")) {
        attr.parse_nested_meta(|meta| {
            if meta.path.is_ident("unit") {
                c.unit = Some(meta.value()?.parse::<LitStr>()?.value());
            } else if meta.path.is_ident("skip") {
                c.skip = true;
            } else if meta.path.is_ident("nested") {
                c.nested = true;
            } else if meta.path.is_ident("first") {
                c.first = true;
            } else if meta.path.is_ident("only") {
                let list = meta.value()?.parse::<LitStr>()?.value();
                c.only = list
                    .split(',')
                    .map(|n| n.trim().to_string())
                    .filter(|n| !n.is_empty())
                    .collect();
            } else {
                return Err(meta.error("expected unit, skip, nested, first or only"));
            }
            Ok(())
        })?;
    }
    if c.skip && (c.nested || c.first || c.unit.is_some() || !c.only.is_empty()) {
        return Err(Error::new_spanned(&attrs[0], "#[column(skip)] goes alone"));
    }
    Ok(c)
}
