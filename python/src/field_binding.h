// Python attributes from a struct's field list (plateball/field_list.h), as Drake's
// DefAttributesUsingSerialize derives them from its Serialize(Archive*): for each field a property
// whose docstring is the field's documentation line, whose setter converts the value itself (a
// wrong type is a TypeError "CLASS.FIELD: value V: must be TYPE"), and a __repr__ listing every
// field as name=repr(value). Every field is an attribute, ByHand and NotInFile ones too: those
// marks concern problem files only.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "bind_common.h"
#include "plateball/field_list.h"

// Hidden like pybind11's own types, which these hold (namespace plateball has default visibility).
#if defined(__GNUC__) || defined(__clang__)
#define PLATEBALL_PYTHON_HIDDEN __attribute__((visibility("hidden")))
#else
#define PLATEBALL_PYTHON_HIDDEN
#endif

namespace plateball::python {

/// A setter's argument that every Python object loads into, so that the setter converts it itself
/// and names the field in its error; signatures and stubs show the field's own type T.
template <class T>
struct PLATEBALL_PYTHON_HIDDEN FieldArgument {
  py::handle object;
};

}  // namespace plateball::python

namespace pybind11::detail {
template <class T>
struct type_caster<plateball::python::FieldArgument<T>> {
  PYBIND11_TYPE_CASTER(plateball::python::FieldArgument<T>, make_caster<T>::name);
  bool load(handle src, bool /*convert*/) {
    value.object = src;
    return true;
  }
};
}  // namespace pybind11::detail

namespace plateball::python {

/// T's Python type as pybind11's signatures write it ("float", "int", "Optional[numpy.ndarray[...]]",
/// "plateball._plateball.IntegrationOptions"): the "must be" of a wrong type.
template <class T>
std::string PythonTypeText() {
  constexpr auto descr = py::detail::make_caster<T>::name;
  const auto types = decltype(descr)::types();
  std::string text;
  std::size_t next = 0;
  for (const char* c = descr.text; *c; ++c) {
    if (*c != '%') {
      text += *c;
      continue;
    }
    const std::type_info* t = types[next++];
    if (const auto* info = t ? py::detail::get_type_info(*t) : nullptr) {
      const py::handle type(reinterpret_cast<PyObject*>(info->type));
      text += py::str(type.attr("__module__")).cast<std::string>() + "." +
              py::str(type.attr("__qualname__")).cast<std::string>();
    } else {
      std::string name = t ? t->name() : "object";
      py::detail::clean_type_id(name);
      text += name;
    }
  }
  return text;
}

/// Defines the properties of a struct's fields on `cls` (see the header comment) and returns
/// their names in list order. A field is addressed by its offset in the struct, taken from a
/// default value's field list.
template <class C>
class PLATEBALL_PYTHON_HIDDEN PropertyArchive {
 public:
  PropertyArchive(py::class_<C>* cls, const C* prototype) : cls_(cls), prototype_(prototype) {}

  template <class... T>
  void Visit(const FieldSpec<T>&... f) {
    (Define(f), ...);
  }
  const std::vector<std::string>& names() const { return names_; }

 private:
  template <class T>
  static T& Member(C& c, std::ptrdiff_t offset) {
    return *reinterpret_cast<T*>(reinterpret_cast<char*>(&c) + offset);
  }
  template <class T>
  static const T& Member(const C& c, std::ptrdiff_t offset) {
    return *reinterpret_cast<const T*>(reinterpret_cast<const char*>(&c) + offset);
  }

  template <class T>
  void Define(const FieldSpec<T>& f) {
    const std::ptrdiff_t offset = reinterpret_cast<const char*>(f.value) - reinterpret_cast<const char*>(prototype_);
    const std::string name = f.name;
    const std::string doc = f.hint ? std::string(f.doc) + "; " + f.hint : std::string(f.doc);
    py::cpp_function get([offset](const C& c) -> const T& { return Member<T>(c, offset); }, py::is_method(*cls_));
    py::cpp_function set(
        [offset, name](C& c, FieldArgument<T> v) {
          try {
            Member<T>(c, offset) = py::cast<T>(v.object);
          } catch (const py::cast_error&) {
            throw py::type_error(std::string(py::str(py::type::of<C>().attr("__name__"))) + "." + name + ": value " +
                                 std::string(py::repr(v.object)) + ": must be " + PythonTypeText<T>());
          }
        },
        py::is_method(*cls_));
    // The getter's policy is reference_internal, as for pybind11's read-write members: a nested value is a view.
    cls_->def_property(name.c_str(), get, set, py::return_value_policy::reference_internal, doc.c_str());
    names_.push_back(name);
  }

  py::class_<C>* cls_;
  const C* prototype_;
  std::vector<std::string> names_;
};

/// The properties of C's field list and `CLASS(field=repr(value), ...)` as __repr__ (eval-able
/// when the values' reprs are).
template <class C>
py::class_<C>& DefFieldAttributes(py::class_<C>& cls) {
  C prototype{};
  PropertyArchive<C> archive(&cls, &prototype);
  prototype.Serialize(&archive);
  cls.def(
      "__repr__",
      [names = archive.names()](const py::object& self) {
        std::string text = std::string(py::str(py::type::of(self).attr("__name__"))) + "(";
        for (std::size_t i = 0; i < names.size(); ++i)
          text += (i ? ", " : "") + names[i] + "=" + std::string(py::repr(self.attr(names[i].c_str())));
        return text + ")";
      },
      "CLASS(field=value, ...) with every field of the options, values as repr() writes them.");
  return cls;
}

}  // namespace plateball::python
