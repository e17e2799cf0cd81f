//! The floating-point leaves of a request, by field: what [`super::Request::validate`] reads
//! to refuse NaN and infinities.
//!
//! A request's serde form is JSON, where a non-finite number has no spelling: `serde_json`
//! writes NaN and ±∞ as `null`, the same as an unset optional field, so a rule applied to the
//! JSON value never sees them. [`floats`] serialises the request once more through a small
//! [`Serializer`] that keeps every `f64`/`f32` it meets, under the name of the top-level field
//! it belongs to (a `#[serde(flatten)]` part's fields count as top-level, as in the JSON;
//! the numbers of a list, an `Option` or a nested struct count under their field).

use serde::ser::{self, Impossible, Serialize, Serializer};
use std::fmt;

/// Every floating-point number of `value`'s serde form, with the top-level field holding it.
///
/// ```
/// #[derive(serde::Serialize)]
/// struct Run { t_end: f64, damping: Option<f64>, grid: Vec<f64>, sides: usize }
/// let run = Run { t_end: f64::NAN, damping: Some(2.0), grid: vec![0.5, f64::INFINITY], sides: 8 };
/// let leaves = tensegrity_core::request::floats(&run);
/// assert_eq!(leaves.len(), 4);
/// assert!(leaves[0].0 == "t_end" && leaves[0].1.is_nan());
/// assert_eq!(leaves[1], ("damping".to_string(), 2.0));
/// assert_eq!(leaves[3], ("grid".to_string(), f64::INFINITY));
/// ```
pub fn floats<T: Serialize + ?Sized>(value: &T) -> Vec<(String, f64)> {
    let mut c = Collector::default();
    // a serialiser that never fails: the error type exists only to satisfy serde
    let _ = value.serialize(&mut c);
    c.out
}

#[derive(Default)]
struct Collector {
    out: Vec<(String, f64)>,
    /// The top-level field being serialised.
    key: String,
    /// How many compound values (structs, maps, lists) enclose the current one.
    depth: usize,
}

/// Never raised: serde's error bound needs one.
#[derive(Debug)]
struct Never;

impl fmt::Display for Never {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("unreachable")
    }
}

impl std::error::Error for Never {}

impl ser::Error for Never {
    fn custom<T: fmt::Display>(_: T) -> Self {
        Never
    }
}

type R = Result<(), Never>;

impl Collector {
    fn push(&mut self, x: f64) -> R {
        self.out.push((self.key.clone(), x));
        Ok(())
    }

    fn open(&mut self) -> Result<&mut Self, Never> {
        self.depth += 1;
        Ok(self)
    }

    fn close(&mut self) -> R {
        self.depth -= 1;
        Ok(())
    }

    /// A field of the top-level struct (or of a flattened part) names what follows.
    fn field<T: Serialize + ?Sized>(&mut self, key: &str, value: &T) -> R {
        if self.depth == 1 {
            self.key = key.to_string();
        }
        value.serialize(self)
    }
}

macro_rules! ignore {
    ($($f:ident($t:ty)),*) => {$(
        fn $f(self, _: $t) -> R { Ok(()) }
    )*};
}

impl Serializer for &mut Collector {
    type Ok = ();
    type Error = Never;
    type SerializeSeq = Self;
    type SerializeTuple = Self;
    type SerializeTupleStruct = Self;
    type SerializeTupleVariant = Self;
    type SerializeMap = Self;
    type SerializeStruct = Self;
    type SerializeStructVariant = Self;

    ignore!(
        serialize_bool(bool),
        serialize_i8(i8),
        serialize_i16(i16),
        serialize_i32(i32),
        serialize_i64(i64),
        serialize_u8(u8),
        serialize_u16(u16),
        serialize_u32(u32),
        serialize_u64(u64),
        serialize_i128(i128),
        serialize_u128(u128),
        serialize_char(char),
        serialize_str(&str),
        serialize_bytes(&[u8]),
        serialize_unit_struct(&'static str)
    );

    fn serialize_f32(self, v: f32) -> R {
        self.push(f64::from(v))
    }
    fn serialize_f64(self, v: f64) -> R {
        self.push(v)
    }
    fn serialize_none(self) -> R {
        Ok(())
    }
    fn serialize_some<T: Serialize + ?Sized>(self, v: &T) -> R {
        v.serialize(self)
    }
    fn serialize_unit(self) -> R {
        Ok(())
    }
    fn serialize_unit_variant(self, _: &'static str, _: u32, _: &'static str) -> R {
        Ok(())
    }
    fn serialize_newtype_struct<T: Serialize + ?Sized>(self, _: &'static str, v: &T) -> R {
        v.serialize(self)
    }
    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        v: &T,
    ) -> R {
        v.serialize(self)
    }
    fn serialize_seq(self, _: Option<usize>) -> Result<Self, Never> {
        self.open()
    }
    fn serialize_tuple(self, _: usize) -> Result<Self, Never> {
        self.open()
    }
    fn serialize_tuple_struct(self, _: &'static str, _: usize) -> Result<Self, Never> {
        self.open()
    }
    fn serialize_tuple_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> Result<Self, Never> {
        self.open()
    }
    fn serialize_map(self, _: Option<usize>) -> Result<Self, Never> {
        self.open()
    }
    fn serialize_struct(self, _: &'static str, _: usize) -> Result<Self, Never> {
        self.open()
    }
    fn serialize_struct_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> Result<Self, Never> {
        self.open()
    }
}

macro_rules! elements {
    ($($trait:ident :: $f:ident),*) => {$(
        impl<'a> ser::$trait for &'a mut Collector {
            type Ok = ();
            type Error = Never;
            fn $f<T: Serialize + ?Sized>(&mut self, v: &T) -> R {
                v.serialize(&mut **self)
            }
            fn end(self) -> R {
                self.close()
            }
        }
    )*};
}

elements!(
    SerializeSeq::serialize_element,
    SerializeTuple::serialize_element,
    SerializeTupleStruct::serialize_field,
    SerializeTupleVariant::serialize_field
);

impl ser::SerializeStruct for &mut Collector {
    type Ok = ();
    type Error = Never;
    fn serialize_field<T: Serialize + ?Sized>(&mut self, key: &'static str, v: &T) -> R {
        self.field(key, v)
    }
    fn end(self) -> R {
        self.close()
    }
}

impl ser::SerializeStructVariant for &mut Collector {
    type Ok = ();
    type Error = Never;
    fn serialize_field<T: Serialize + ?Sized>(&mut self, _: &'static str, v: &T) -> R {
        v.serialize(&mut **self)
    }
    fn end(self) -> R {
        self.close()
    }
}

impl ser::SerializeMap for &mut Collector {
    type Ok = ();
    type Error = Never;
    /// A map's key (the fields of a flattened part arrive as map entries): its text names
    /// the field at the top level.
    fn serialize_key<T: Serialize + ?Sized>(&mut self, key: &T) -> R {
        if self.depth == 1 {
            self.key = key.serialize(KeyText).unwrap_or_default();
        }
        Ok(())
    }
    fn serialize_value<T: Serialize + ?Sized>(&mut self, v: &T) -> R {
        v.serialize(&mut **self)
    }
    fn end(self) -> R {
        self.close()
    }
}

/// The text of a map key (a field name): strings only.
struct KeyText;

macro_rules! no_text {
    ($($f:ident($t:ty)),*) => {$(
        fn $f(self, _: $t) -> Result<String, Never> { Err(Never) }
    )*};
}

impl Serializer for KeyText {
    type Ok = String;
    type Error = Never;
    type SerializeSeq = Impossible<String, Never>;
    type SerializeTuple = Impossible<String, Never>;
    type SerializeTupleStruct = Impossible<String, Never>;
    type SerializeTupleVariant = Impossible<String, Never>;
    type SerializeMap = Impossible<String, Never>;
    type SerializeStruct = Impossible<String, Never>;
    type SerializeStructVariant = Impossible<String, Never>;

    fn serialize_str(self, v: &str) -> Result<String, Never> {
        Ok(v.to_string())
    }
    no_text!(
        serialize_bool(bool),
        serialize_i8(i8),
        serialize_i16(i16),
        serialize_i32(i32),
        serialize_i64(i64),
        serialize_u8(u8),
        serialize_u16(u16),
        serialize_u32(u32),
        serialize_u64(u64),
        serialize_f32(f32),
        serialize_f64(f64),
        serialize_char(char),
        serialize_bytes(&[u8]),
        serialize_unit_struct(&'static str)
    );
    fn serialize_none(self) -> Result<String, Never> {
        Err(Never)
    }
    fn serialize_some<T: Serialize + ?Sized>(self, _: &T) -> Result<String, Never> {
        Err(Never)
    }
    fn serialize_unit(self) -> Result<String, Never> {
        Err(Never)
    }
    fn serialize_unit_variant(
        self,
        _: &'static str,
        _: u32,
        v: &'static str,
    ) -> Result<String, Never> {
        Ok(v.to_string())
    }
    fn serialize_newtype_struct<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        v: &T,
    ) -> Result<String, Never> {
        v.serialize(self)
    }
    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: &T,
    ) -> Result<String, Never> {
        Err(Never)
    }
    fn serialize_seq(self, _: Option<usize>) -> Result<Self::SerializeSeq, Never> {
        Err(Never)
    }
    fn serialize_tuple(self, _: usize) -> Result<Self::SerializeTuple, Never> {
        Err(Never)
    }
    fn serialize_tuple_struct(
        self,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeTupleStruct, Never> {
        Err(Never)
    }
    fn serialize_tuple_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeTupleVariant, Never> {
        Err(Never)
    }
    fn serialize_map(self, _: Option<usize>) -> Result<Self::SerializeMap, Never> {
        Err(Never)
    }
    fn serialize_struct(self, _: &'static str, _: usize) -> Result<Self::SerializeStruct, Never> {
        Err(Never)
    }
    fn serialize_struct_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeStructVariant, Never> {
        Err(Never)
    }
}
