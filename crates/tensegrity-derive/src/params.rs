//! `#[derive(Params)]`: the description of a request's fields (`Vec<Param>`), declared on
//! the fields (the crate docs give the rule).

use crate::serde_attrs;
use proc_macro2::TokenStream as Tokens;
use quote::quote;
use syn::{Attribute, Data, DeriveInput, Error, Expr, Fields, LitStr};

pub(crate) fn expand(input: &DeriveInput) -> syn::Result<Tokens> {
    if !input.generics.params.is_empty() {
        return Err(Error::new_spanned(
            &input.generics,
            "#[derive(Params)] takes no generic type",
        ));
    }
    let Data::Struct(s) = &input.data else {
        return Err(Error::new_spanned(
            &input.ident,
            "#[derive(Params)] takes a struct",
        ));
    };
    let Fields::Named(named) = &s.fields else {
        return Err(Error::new_spanned(
            &s.fields,
            "#[derive(Params)] takes named fields only",
        ));
    };
    if serde_attrs(&input.attrs)?.rename_all {
        return Err(Error::new_spanned(
            &input.ident,
            "#[derive(Params)] does not follow rename_all on fields",
        ));
    }
    let order = order_attr(&input.attrs)?;
    let mut body = Tokens::new();
    for f in &named.named {
        let serde = serde_attrs(&f.attrs)?;
        let param = param_attrs(&f.attrs)?;
        if serde.skip {
            if param.given {
                return Err(Error::new_spanned(f, "a skipped field has no parameter"));
            }
            continue;
        }
        if serde.flatten || param.flatten {
            if param.kind.is_some() || param.help.is_some() || param.unit.is_some() {
                return Err(Error::new_spanned(
                    f,
                    "a flattened field takes its type's parameters: #[param(flatten)] goes alone",
                ));
            }
            let ty = &f.ty;
            body.extend(quote! {
                p.extend(<#ty as ::tensegrity_core::request::Params>::params());
            });
            continue;
        }
        let ident = f.ident.as_ref().expect("named field");
        let name = serde
            .rename
            .unwrap_or_else(|| ident.to_string().trim_start_matches("r#").to_string());
        let kind = param.kind.ok_or_else(|| {
            Error::new_spanned(
                f,
                "a request field needs #[param(<kind>, help = …)] (kind: number, count, angle, \
                 flag, choice = …, text, counts, numbers), or #[param(flatten)]",
            )
        })?;
        let help = param
            .help
            .ok_or_else(|| Error::new_spanned(f, "a parameter needs `help = …`"))?;
        let k = quote! { ::tensegrity_core::request::Kind };
        let (kind, unit) = match kind {
            ParamKind::Number => (quote! { #k::Number }, ""),
            ParamKind::Count => (quote! { #k::Count }, ""),
            ParamKind::Angle => (quote! { #k::Angle }, "rad"),
            ParamKind::Flag => (quote! { #k::Flag }, ""),
            ParamKind::Text => (quote! { #k::Text }, ""),
            ParamKind::Counts => (quote! { #k::Counts }, ""),
            ParamKind::Numbers => (quote! { #k::Numbers }, ""),
            ParamKind::Choice(Expr::Array(a)) => (quote! { #k::Choice(&#a) }, ""),
            ParamKind::Choice(e) => (quote! { #k::Choice(#e) }, ""),
        };
        let unit = param.unit.unwrap_or_else(|| unit.to_string());
        let mut modifiers = Tokens::new();
        if let Some(rule) = param.rule {
            modifiers.extend(quote! {
                .rule({
                    #[allow(unused_imports)]
                    use ::tensegrity_core::request::Rule::{self, *};
                    #rule
                })
            });
        }
        if param.optional {
            modifiers.extend(quote! { .optional() });
        }
        if param.required {
            modifiers.extend(quote! { .required() });
        }
        body.extend(quote! {
            p.push(
                ::tensegrity_core::request::Param::new(#name, #kind, #unit, #help) #modifiers
            );
        });
    }
    let arrange = match order {
        Some(names) => quote! { let p = ::tensegrity_core::request::arrange(p, &[#(#names),*]); },
        None => Tokens::new(),
    };
    let name = &input.ident;
    Ok(quote! {
        impl ::tensegrity_core::request::Params for #name {
            fn params() -> ::std::vec::Vec<::tensegrity_core::request::Param> {
                #[allow(unused_mut)]
                let mut p = ::std::vec::Vec::new();
                #body
                #arrange
                p
            }
        }
    })
}

/// The kind word of `#[param(…)]`.
enum ParamKind {
    Number,
    Count,
    Angle,
    Flag,
    Text,
    Counts,
    Numbers,
    Choice(Expr),
}

/// What the `#[param(…)]` attributes of a field say.
#[derive(Default)]
struct ParamAttrs {
    given: bool,
    kind: Option<ParamKind>,
    unit: Option<String>,
    help: Option<Expr>,
    rule: Option<Expr>,
    optional: bool,
    required: bool,
    flatten: bool,
}

fn param_attrs(attrs: &[Attribute]) -> syn::Result<ParamAttrs> {
    let mut p = ParamAttrs::default();
    for attr in attrs.iter().filter(|a| a.path().is_ident("param")) {
        p.given = true;
        attr.parse_nested_meta(|meta| {
            let path = &meta.path;
            let word = |w: &str| path.is_ident(w);
            let simple = [
                ("number", ParamKind::Number),
                ("count", ParamKind::Count),
                ("angle", ParamKind::Angle),
                ("flag", ParamKind::Flag),
                ("text", ParamKind::Text),
                ("counts", ParamKind::Counts),
                ("numbers", ParamKind::Numbers),
            ];
            let kind = if let Some((_, k)) = simple.into_iter().find(|(w, _)| word(w)) {
                Some(k)
            } else if word("choice") {
                Some(ParamKind::Choice(meta.value()?.parse::<Expr>()?))
            } else {
                None
            };
            if let Some(k) = kind {
                if p.kind.replace(k).is_some() {
                    return Err(meta.error("one kind per parameter"));
                }
            } else if word("unit") {
                p.unit = Some(meta.value()?.parse::<LitStr>()?.value());
            } else if word("help") {
                p.help = Some(meta.value()?.parse::<Expr>()?);
            } else if word("rule") {
                p.rule = Some(meta.value()?.parse::<Expr>()?);
            } else if word("positive") {
                p.rule = Some(syn::parse_quote!(Rule::Positive));
            } else if word("non_negative") {
                p.rule = Some(syn::parse_quote!(Rule::NonNegative));
            } else if word("optional") {
                p.optional = true;
            } else if word("required") {
                p.required = true;
            } else if word("flatten") {
                p.flatten = true;
            } else {
                return Err(meta.error(
                    "expected a kind (number, count, angle, flag, choice = …, text, counts, \
                     numbers), unit, help, rule, positive, non_negative, optional, required \
                     or flatten",
                ));
            }
            Ok(())
        })?;
    }
    Ok(p)
}

/// The names of `#[params(order = "a, b, …")]`.
fn order_attr(attrs: &[Attribute]) -> syn::Result<Option<Vec<String>>> {
    let mut order = None;
    for attr in attrs.iter().filter(|a| a.path().is_ident("params")) {
        attr.parse_nested_meta(|meta| {
            if meta.path.is_ident("order") {
                let list = meta.value()?.parse::<LitStr>()?.value();
                order = Some(
                    list.split(',')
                        .map(|n| n.trim().to_string())
                        .filter(|n| !n.is_empty())
                        .collect(),
                );
                Ok(())
            } else {
                Err(meta.error("expected order"))
            }
        })?;
    }
    Ok(order)
}
