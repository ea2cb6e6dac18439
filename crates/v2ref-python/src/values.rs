//! The library's answers as Python objects, built directly from their
//! `Serialize` implementation (no JSON text between Rust and Python): a
//! struct or map becomes a `dict` (fields in their declaration order, as
//! the CLI's `--json` writes them), a sequence a `list`, a number an `int`
//! or `float`, a unit or `None` `None`, an enum's unit variant its name —
//! the same objects as `json.loads` of the CLI's text, non-finite numbers
//! included (`None`, as JSON writes them). And a sidecar given as a dict
//! made a JSON value for the library's reader.

use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyString};
use pyo3::IntoPyObjectExt;
use serde::ser::{self, Serialize};

/// `value` as a Python object.
pub fn to_py<T: Serialize + ?Sized>(py: Python<'_>, value: &T) -> PyResult<PyObject> {
    value.serialize(ToPy { py }).map_err(|e| e.0)
}

/// A Python object given as a JSON document (a sidecar's dict) as a JSON
/// value: dict (string keys), list or tuple, str, int, float, bool, None.
/// A non-finite float is refused, as JSON cannot hold it.
pub fn to_json(param: &str, obj: &Bound<'_, PyAny>) -> PyResult<serde_json::Value> {
    use serde_json::Value;
    if obj.is_none() {
        return Ok(Value::Null);
    }
    if let Ok(b) = obj.downcast::<pyo3::types::PyBool>() {
        return Ok(Value::Bool(b.is_true()));
    }
    if let Ok(s) = obj.downcast::<PyString>() {
        return Ok(Value::String(s.to_cow()?.into_owned()));
    }
    if let Ok(d) = obj.downcast::<PyDict>() {
        let mut map = serde_json::Map::new();
        for (k, v) in d.iter() {
            let key: String = k
                .extract()
                .map_err(|_| PyTypeError::new_err(format!("{param}: key {k} is not a string")))?;
            map.insert(key, to_json(param, &v)?);
        }
        return Ok(Value::Object(map));
    }
    if obj.downcast::<PyList>().is_ok() || obj.downcast::<pyo3::types::PyTuple>().is_ok() {
        let items: PyResult<Vec<Value>> = obj.try_iter()?.map(|x| to_json(param, &x?)).collect();
        return Ok(Value::Array(items?));
    }
    if let Ok(i) = obj.extract::<i64>() {
        return Ok(Value::from(i));
    }
    if let Ok(u) = obj.extract::<u64>() {
        return Ok(Value::from(u));
    }
    if let Ok(x) = obj.extract::<f64>() {
        return serde_json::Number::from_f64(x)
            .map(Value::Number)
            .ok_or_else(|| PyValueError::new_err(format!("{param}: {x} is not a JSON number")));
    }
    Err(PyTypeError::new_err(format!(
        "{param}: a {} is not a JSON value",
        obj.get_type().name()?
    )))
}

/// A failed conversion (a Python error, or a serde error as `ValueError`).
#[derive(Debug)]
pub struct ToPyError(PyErr);

impl std::fmt::Display for ToPyError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.0.fmt(f)
    }
}

impl std::error::Error for ToPyError {}

impl ser::Error for ToPyError {
    fn custom<T: std::fmt::Display>(msg: T) -> Self {
        ToPyError(PyValueError::new_err(format!(
            "cannot convert the answer: {msg}"
        )))
    }
}

impl From<PyErr> for ToPyError {
    fn from(e: PyErr) -> Self {
        ToPyError(e)
    }
}

type Out = Result<PyObject, ToPyError>;

/// The serializer: each value made a Python object.
#[derive(Clone, Copy)]
struct ToPy<'py> {
    py: Python<'py>,
}

impl<'py> ToPy<'py> {
    fn any<T: IntoPyObject<'py>>(self, v: T) -> Out {
        Ok(v.into_py_any(self.py)?)
    }

    fn dict(self) -> Compound<'py> {
        Compound::Dict(PyDict::new(self.py), None)
    }

    fn list(self) -> Compound<'py> {
        Compound::List(PyList::empty(self.py))
    }

    /// `{variant: value}`, as serde_json writes a variant holding data.
    fn tagged(self, variant: &'static str, value: PyObject) -> Out {
        let d = PyDict::new(self.py);
        d.set_item(variant, value)?;
        Ok(d.into_any().unbind())
    }
}

/// A dict or list being filled; a variant's data is wrapped in
/// `{variant: …}` when it ends.
enum Compound<'py> {
    Dict(Bound<'py, PyDict>, Option<Bound<'py, PyAny>>),
    List(Bound<'py, PyList>),
    Variant(&'static str, Box<Compound<'py>>, ToPy<'py>),
}

impl<'py> Compound<'py> {
    fn py(&self) -> Python<'py> {
        match self {
            Compound::Dict(d, _) => d.py(),
            Compound::List(l) => l.py(),
            Compound::Variant(_, _, s) => s.py,
        }
    }

    /// Appends `v` made a Python object (to a sequence).
    fn push<T: Serialize + ?Sized>(&mut self, v: &T) -> Result<(), ToPyError> {
        let v = v.serialize(ToPy { py: self.py() })?;
        self.append(v)
    }

    fn append(&mut self, v: PyObject) -> Result<(), ToPyError> {
        match self {
            Compound::List(l) => Ok(l.append(v)?),
            Compound::Variant(_, inner, _) => inner.append(v),
            Compound::Dict(..) => Err(ser::Error::custom("a value without a key")),
        }
    }

    /// Sets the field `k` to `v` made a Python object (in a struct).
    fn field<T: Serialize + ?Sized>(&mut self, k: &str, v: &T) -> Result<(), ToPyError> {
        let v = v.serialize(ToPy { py: self.py() })?;
        self.set(k, v)
    }

    fn set(&mut self, k: &str, v: PyObject) -> Result<(), ToPyError> {
        match self {
            Compound::Dict(d, _) => Ok(d.set_item(k, v)?),
            Compound::Variant(_, inner, _) => inner.set(k, v),
            Compound::List(_) => Err(ser::Error::custom("a key in a sequence")),
        }
    }

    fn finish(self) -> Out {
        match self {
            Compound::Dict(d, _) => Ok(d.into_any().unbind()),
            Compound::List(l) => Ok(l.into_any().unbind()),
            Compound::Variant(name, inner, s) => s.tagged(name, inner.finish()?),
        }
    }
}

/// The serializer's methods of the plain values Python converts itself
/// (`ToPy::any`).
macro_rules! serialize_any {
    ($($method:ident: $ty:ty),*) => {$(
        fn $method(self, v: $ty) -> Out {
            self.any(v)
        }
    )*};
}

impl<'py> ser::Serializer for ToPy<'py> {
    type Ok = PyObject;
    type Error = ToPyError;
    type SerializeSeq = Compound<'py>;
    type SerializeTuple = Compound<'py>;
    type SerializeTupleStruct = Compound<'py>;
    type SerializeTupleVariant = Compound<'py>;
    type SerializeMap = Compound<'py>;
    type SerializeStruct = Compound<'py>;
    type SerializeStructVariant = Compound<'py>;

    serialize_any!(
        serialize_bool: bool,
        serialize_i8: i8,
        serialize_i16: i16,
        serialize_i32: i32,
        serialize_i64: i64,
        serialize_u8: u8,
        serialize_u16: u16,
        serialize_u32: u32,
        serialize_u64: u64
    );
    fn serialize_f32(self, v: f32) -> Out {
        self.serialize_f64(f64::from(v))
    }
    /// A non-finite number is `None`, as JSON writes it (`null`).
    fn serialize_f64(self, v: f64) -> Out {
        match v.is_finite() {
            true => self.any(v),
            false => Ok(self.py.None()),
        }
    }
    fn serialize_char(self, v: char) -> Out {
        self.any(v.to_string())
    }
    fn serialize_str(self, v: &str) -> Out {
        self.any(v)
    }
    fn serialize_bytes(self, v: &[u8]) -> Out {
        self.any(v.to_vec())
    }
    fn serialize_none(self) -> Out {
        Ok(self.py.None())
    }
    fn serialize_some<T: Serialize + ?Sized>(self, v: &T) -> Out {
        v.serialize(self)
    }
    fn serialize_unit(self) -> Out {
        Ok(self.py.None())
    }
    fn serialize_unit_struct(self, _: &'static str) -> Out {
        Ok(self.py.None())
    }
    fn serialize_unit_variant(self, _: &'static str, _: u32, variant: &'static str) -> Out {
        self.any(variant)
    }
    fn serialize_newtype_struct<T: Serialize + ?Sized>(self, _: &'static str, v: &T) -> Out {
        v.serialize(self)
    }
    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
        v: &T,
    ) -> Out {
        let inner = v.serialize(self)?;
        self.tagged(variant, inner)
    }
    fn serialize_seq(self, _: Option<usize>) -> Result<Compound<'py>, ToPyError> {
        Ok(self.list())
    }
    fn serialize_tuple(self, _: usize) -> Result<Compound<'py>, ToPyError> {
        Ok(self.list())
    }
    fn serialize_tuple_struct(self, _: &'static str, _: usize) -> Result<Compound<'py>, ToPyError> {
        Ok(self.list())
    }
    fn serialize_tuple_variant(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
        _: usize,
    ) -> Result<Compound<'py>, ToPyError> {
        Ok(Compound::Variant(variant, Box::new(self.list()), self))
    }
    fn serialize_map(self, _: Option<usize>) -> Result<Compound<'py>, ToPyError> {
        Ok(self.dict())
    }
    fn serialize_struct(self, _: &'static str, _: usize) -> Result<Compound<'py>, ToPyError> {
        Ok(self.dict())
    }
    fn serialize_struct_variant(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
        _: usize,
    ) -> Result<Compound<'py>, ToPyError> {
        Ok(Compound::Variant(variant, Box::new(self.dict()), self))
    }
}

/// The compounds of a list (a sequence, a tuple, a tuple struct or
/// variant): each element pushed, the list (or tagged variant) returned.
macro_rules! list_compound {
    ($($kind:ident: $element:ident),*) => {$(
        impl ser::$kind for Compound<'_> {
            type Ok = PyObject;
            type Error = ToPyError;
            fn $element<T: Serialize + ?Sized>(&mut self, v: &T) -> Result<(), ToPyError> {
                self.push(v)
            }
            fn end(self) -> Out {
                self.finish()
            }
        }
    )*};
}

list_compound!(
    SerializeSeq: serialize_element,
    SerializeTuple: serialize_element,
    SerializeTupleStruct: serialize_field,
    SerializeTupleVariant: serialize_field
);

impl ser::SerializeMap for Compound<'_> {
    type Ok = PyObject;
    type Error = ToPyError;
    /// A key is kept as a string (JSON's object keys are strings).
    fn serialize_key<T: Serialize + ?Sized>(&mut self, k: &T) -> Result<(), ToPyError> {
        let py = self.py();
        let key = k.serialize(ToPy { py })?.into_bound(py);
        let key = match key.downcast::<PyString>() {
            Ok(_) => key,
            Err(_) => key.str()?.into_any(),
        };
        match self {
            Compound::Dict(_, pending) => *pending = Some(key),
            _ => return Err(ser::Error::custom("a key outside a map")),
        }
        Ok(())
    }
    fn serialize_value<T: Serialize + ?Sized>(&mut self, v: &T) -> Result<(), ToPyError> {
        let py = self.py();
        let v = v.serialize(ToPy { py })?;
        match self {
            Compound::Dict(d, pending) => {
                let key = pending
                    .take()
                    .ok_or_else(|| <ToPyError as ser::Error>::custom("a value without a key"))?;
                d.set_item(key, v)?;
            }
            _ => return Err(ser::Error::custom("a value outside a map")),
        }
        Ok(())
    }
    fn end(self) -> Out {
        self.finish()
    }
}

/// The compounds of named fields (a struct or a struct variant): each
/// field set, the dict (or tagged variant) returned.
macro_rules! struct_compound {
    ($($kind:ident),*) => {$(
        impl ser::$kind for Compound<'_> {
            type Ok = PyObject;
            type Error = ToPyError;
            fn serialize_field<T: Serialize + ?Sized>(
                &mut self,
                k: &'static str,
                v: &T,
            ) -> Result<(), ToPyError> {
                self.field(k, v)
            }
            fn end(self) -> Out {
                self.finish()
            }
        }
    )*};
}

struct_compound!(SerializeStruct, SerializeStructVariant);

/// A sidecar given from Python: the text of a SET.json file (a `str`) or
/// the dict `synthesize` returned, as a JSON value (`None` for a text).
pub enum SidecarArg {
    /// The text of a file.
    Text(String),
    /// A dict.
    Value(serde_json::Value),
}

impl SidecarArg {
    /// The sidecar argument `obj`.
    pub fn of(obj: &Bound<'_, PyAny>) -> PyResult<SidecarArg> {
        match obj.downcast::<PyString>() {
            Ok(s) => Ok(SidecarArg::Text(s.to_cow()?.into_owned())),
            Err(_) => Ok(SidecarArg::Value(to_json("sidecar", obj)?)),
        }
    }
}
