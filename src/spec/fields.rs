//! The field paths a campaign file accepts, read from the serde derives that parse it.
//!
//! `RawCampaign` and `RawScene` are derived `Deserialize` structs with `deny_unknown_fields`:
//! the keys they accept are exactly the `fields` list each derive hands to
//! `Deserializer::deserialize_struct`. [`FieldRecorder`] is a deserializer that writes those
//! lists down, section by section, and answers every value with a stand-in (the first variant
//! of an enum, `0`, `""`, one element of a list), so the derives themselves walk every nested
//! struct. No list here is written by hand: a field added to `raw.rs` shows up in these paths.
//! (A `#[serde(flatten)]` field would hide its keys from this walk: none is used.)

use serde::de::value::{Error, StrDeserializer};
use serde::de::{
    DeserializeSeed, Deserializer, EnumAccess, IntoDeserializer, MapAccess, SeqAccess, VariantAccess, Visitor,
};
use std::cell::RefCell;
use std::collections::BTreeSet;

use super::raw::{RawCampaign, RawScene};

/// Every field path of a scene (`defaults:` and each entry of `scenes:`), dotted as a grid
/// writes it (`material.mass`, `lattice.type`, `relax.tolerance`), sections (`material`)
/// left out: only the keys that hold a value. Sorted.
pub fn scene_fields() -> Vec<String> {
    leaves::<RawScene>(None)
}

/// Every field path of the campaign itself (`version`, `name`, `budget.seconds_per_run`, ...),
/// sections left out; `defaults` and `scenes` are named but not entered (their fields are
/// [`scene_fields`]). Sorted.
pub fn campaign_fields() -> Vec<String> {
    let scene = struct_name::<RawScene>();
    leaves::<RawCampaign>(Some(scene))
}

/// What one walk wrote down.
#[derive(Default)]
struct Record {
    /// Every path met, sections included.
    paths: BTreeSet<String>,
    /// The paths whose value is a struct.
    sections: BTreeSet<String>,
    /// The name the derive gives the outermost struct.
    outermost: Option<&'static str>,
}

/// The value-holding paths of `T`, not entering structs named `opaque`.
fn leaves<T: serde::de::DeserializeOwned>(opaque: Option<&'static str>) -> Vec<String> {
    let record = RefCell::new(Record::default());
    T::deserialize(FieldRecorder { prefix: String::new(), record: &record, opaque })
        .unwrap_or_else(|e| panic!("the field walk of {} failed: {e}", std::any::type_name::<T>()));
    let record = record.into_inner();
    record.paths.difference(&record.sections).cloned().collect()
}

/// The name `T`'s derive passes to `deserialize_struct`.
fn struct_name<T: serde::de::DeserializeOwned>() -> &'static str {
    let record = RefCell::new(Record::default());
    T::deserialize(FieldRecorder { prefix: String::new(), record: &record, opaque: None })
        .unwrap_or_else(|e| panic!("the field walk of {} failed: {e}", std::any::type_name::<T>()));
    record.into_inner().outermost.expect("a struct")
}

/// A deserializer that records the fields of every struct it is asked for, under `prefix`.
struct FieldRecorder<'r> {
    /// The dotted path of the value being read, with a trailing `.` (empty at the top).
    prefix: String,
    record: &'r RefCell<Record>,
    /// A struct whose fields are not entered.
    opaque: Option<&'static str>,
}

impl<'r> FieldRecorder<'r> {
    fn below(&self, key: &str) -> FieldRecorder<'r> {
        FieldRecorder { prefix: format!("{}{key}.", self.prefix), record: self.record, opaque: self.opaque }
    }
    fn again(&self) -> FieldRecorder<'r> {
        FieldRecorder { prefix: self.prefix.clone(), record: self.record, opaque: self.opaque }
    }
}

impl<'de> Deserializer<'de> for FieldRecorder<'_> {
    type Error = Error;

    fn deserialize_struct<V: Visitor<'de>>(
        self,
        name: &'static str,
        fields: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, Error> {
        let entered = self.opaque != Some(name);
        {
            let mut record = self.record.borrow_mut();
            record.outermost.get_or_insert(name);
            if entered {
                if let Some(path) = self.prefix.strip_suffix('.') {
                    record.sections.insert(path.to_string());
                }
                record.paths.extend(fields.iter().map(|field| format!("{}{field}", self.prefix)));
            }
        }
        let fields: &'static [&'static str] = if entered { fields } else { &[] };
        visitor.visit_map(Fields { fields, next: 0, recorder: self })
    }

    // Stand-ins for the values: each is one the field's own `Deserialize` accepts.
    fn deserialize_any<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        visitor.visit_f64(0.0)
    }
    fn deserialize_bool<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        visitor.visit_bool(false)
    }
    fn deserialize_i8<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        visitor.visit_i64(0)
    }
    fn deserialize_i16<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        visitor.visit_i64(0)
    }
    fn deserialize_i32<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        visitor.visit_i64(0)
    }
    fn deserialize_i64<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        visitor.visit_i64(0)
    }
    fn deserialize_u8<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        visitor.visit_u64(0)
    }
    fn deserialize_u16<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        visitor.visit_u64(0)
    }
    fn deserialize_u32<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        visitor.visit_u64(0)
    }
    fn deserialize_u64<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        visitor.visit_u64(0)
    }
    fn deserialize_f32<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        visitor.visit_f64(0.0)
    }
    fn deserialize_f64<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        visitor.visit_f64(0.0)
    }
    fn deserialize_char<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        visitor.visit_char('a')
    }
    fn deserialize_str<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        visitor.visit_str("")
    }
    fn deserialize_string<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        visitor.visit_str("")
    }
    fn deserialize_bytes<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        visitor.visit_bytes(&[])
    }
    fn deserialize_byte_buf<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        visitor.visit_bytes(&[])
    }
    fn deserialize_option<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        visitor.visit_some(self)
    }
    fn deserialize_unit<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        visitor.visit_unit()
    }
    fn deserialize_unit_struct<V: Visitor<'de>>(self, _name: &'static str, visitor: V) -> Result<V::Value, Error> {
        visitor.visit_unit()
    }
    fn deserialize_newtype_struct<V: Visitor<'de>>(self, _name: &'static str, visitor: V) -> Result<V::Value, Error> {
        visitor.visit_newtype_struct(self)
    }
    /// One element, so a list of structs (`scenes`) is entered once.
    fn deserialize_seq<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        visitor.visit_seq(Elements { left: 1, recorder: self })
    }
    fn deserialize_tuple<V: Visitor<'de>>(self, len: usize, visitor: V) -> Result<V::Value, Error> {
        visitor.visit_seq(Elements { left: len, recorder: self })
    }
    fn deserialize_tuple_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        len: usize,
        visitor: V,
    ) -> Result<V::Value, Error> {
        visitor.visit_seq(Elements { left: len, recorder: self })
    }
    /// A map's keys are the user's (a grid's dotted paths), not fields: an empty one.
    fn deserialize_map<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        visitor.visit_map(Fields { fields: &[], next: 0, recorder: self })
    }
    fn deserialize_enum<V: Visitor<'de>>(
        self,
        _name: &'static str,
        variants: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, Error> {
        let first = variants.first().copied().ok_or_else(|| serde::de::Error::custom("an enum without variants"))?;
        visitor.visit_enum(Variant { name: first, recorder: self })
    }
    fn deserialize_identifier<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        visitor.visit_str("")
    }
    fn deserialize_ignored_any<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        visitor.visit_unit()
    }
}

/// A struct's fields, each key followed by its value read from the recorder one level down.
struct Fields<'r> {
    fields: &'static [&'static str],
    next: usize,
    recorder: FieldRecorder<'r>,
}

impl<'de> MapAccess<'de> for Fields<'_> {
    type Error = Error;

    fn next_key_seed<K: DeserializeSeed<'de>>(&mut self, seed: K) -> Result<Option<K::Value>, Error> {
        let Some(field) = self.fields.get(self.next) else { return Ok(None) };
        let key: StrDeserializer<'_, Error> = field.into_deserializer();
        seed.deserialize(key).map(Some)
    }
    fn next_value_seed<V: DeserializeSeed<'de>>(&mut self, seed: V) -> Result<V::Value, Error> {
        let field = self.fields[self.next];
        self.next += 1;
        seed.deserialize(self.recorder.below(field))
    }
}

/// The elements of a list or tuple, each read at the list's own path.
struct Elements<'r> {
    left: usize,
    recorder: FieldRecorder<'r>,
}

impl<'de> SeqAccess<'de> for Elements<'_> {
    type Error = Error;

    fn next_element_seed<T: DeserializeSeed<'de>>(&mut self, seed: T) -> Result<Option<T::Value>, Error> {
        if self.left == 0 {
            return Ok(None);
        }
        self.left -= 1;
        seed.deserialize(self.recorder.again()).map(Some)
    }
}

/// An enum's first variant; a variant with contents reads them from the recorder.
struct Variant<'r> {
    name: &'static str,
    recorder: FieldRecorder<'r>,
}

impl<'de, 'r> EnumAccess<'de> for Variant<'r> {
    type Error = Error;
    type Variant = FieldRecorder<'r>;

    fn variant_seed<V: DeserializeSeed<'de>>(self, seed: V) -> Result<(V::Value, FieldRecorder<'r>), Error> {
        let name: StrDeserializer<'_, Error> = self.name.into_deserializer();
        Ok((seed.deserialize(name)?, self.recorder))
    }
}

impl<'de> VariantAccess<'de> for FieldRecorder<'_> {
    type Error = Error;

    fn unit_variant(self) -> Result<(), Error> {
        Ok(())
    }
    fn newtype_variant_seed<T: DeserializeSeed<'de>>(self, seed: T) -> Result<T::Value, Error> {
        seed.deserialize(self)
    }
    fn tuple_variant<V: Visitor<'de>>(self, len: usize, visitor: V) -> Result<V::Value, Error> {
        visitor.visit_seq(Elements { left: len, recorder: self })
    }
    fn struct_variant<V: Visitor<'de>>(self, fields: &'static [&'static str], visitor: V) -> Result<V::Value, Error> {
        self.deserialize_struct("", fields, visitor)
    }
}
