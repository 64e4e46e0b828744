// pw85._ext: the hot calls of the Python package pw85 compiled (nanobind),
// in place of their ctypes calls (python/pw85/_native.py chooses):
//
//   overlap1(r12, q1, q2, nthreads, check)
//       pw85_overlap of one pair
//   contact_function1(r12, q1, q2, method, nthreads, check)
//       pw85_contact_function_method of one pair
//   overlap_pairs(m, r12, q1, q2, overlap, status, nthreads)
//       pw85_overlap_pairs; overlap: bool (1 byte) per pair
//   contact_function_pairs(m, r12, q1, q2, method, mu2, lambda, status, nthreads)
//       pw85_contact_function_pairs; mu2, lambda: float64 per pair
//
// The one-pair calls take the vectors and matrices as float64 buffers of
// 3 and 6 elements (NumPy arrays of any strides and alignment, bytes views)
// or lists or tuples of floats and ints, and copy them into aligned local
// arrays. They return what the Python function returns for a pair that
// succeeds: the verdict as a bool, or (mu2, lambda) as NumPy float64
// scalars (with a status 0 appended for check=False); None for anything
// else (other arguments, a failing pair), which the Python function then
// converts, computes again and reports (naming what is wrong) as for a
// batch.
//
// The pair calls take the C-contiguous, aligned arrays the Python functions
// prepare (checked here: a ValueError otherwise), status None when the
// per-pair statuses are not wanted, and return the C call's status (PW85_OK
// or that of the first failing pair); the outputs of a failing pair are
// those of the C call (overlap False). Every C call runs without the GIL.
#include <nanobind/nanobind.h>

#include <algorithm>
#include <climits>
#include <cstdint>
#include <cstring>
#include <memory>
#include <new>

#include <pw85.h>

namespace nb = nanobind;

namespace {

// NumPy's float64 type: set once, when the module is imported (NumPy is a
// dependency of pw85), and only read afterwards.
PyObject *float64_type = nullptr;

// A float64 scalar of value x, made as NumPy makes its scalars (tp_alloc
// of the type, then the value): NumPy's double scalar extends Python's
// float, so its value is the float's ob_fval.
PyObject *new_float64(double x) {
  PyTypeObject *type = reinterpret_cast<PyTypeObject *>(float64_type);
  PyObject *scalar = type->tp_alloc(type, 0);
  if (scalar != nullptr) reinterpret_cast<PyFloatObject *>(scalar)->ob_fval = x;
  return scalar;
}

bool is_native_double(const char *format) {
  if (format == nullptr) return true;  // "B" implied; rejected by itemsize
  if (*format == '@' || *format == '=') {
    ++format;
  } else if (*format == '<') {
#if PY_LITTLE_ENDIAN
    ++format;
#else
    return false;
#endif
  }
  return format[0] == 'd' && format[1] == '\0';
}

// The leading fields of NumPy's array object (PyArrayObject_fields of
// numpy/ndarraytypes.h, the same in NumPy 1 and 2; NumPy's own inline
// accessors compiled into every extension read them). Read for arrays of
// the exact type numpy.ndarray with the float64 descriptor only, and only
// once module import has checked them against the buffer protocol on an
// array of its own (numpy_fields_ok): the buffer protocol costs about 600
// instructions per array, more than a one-pair overlap test.
struct NumpyArrayFields {
  PyObject_HEAD
  char *data;
  int nd;
  Py_ssize_t *dimensions;
  Py_ssize_t *strides;
  PyObject *base;
  PyObject *descr;
};

// Set once, when the module is imported, and only read afterwards.
PyTypeObject *ndarray_type = nullptr;
PyObject *float64_descr = nullptr;
bool numpy_fields_ok = false;

// out[0..n) from obj when obj is a 1D buffer of n native doubles (any
// strides and alignment) or a list or tuple of n floats or ints (not
// bools); false (no Python error set) otherwise.
bool read_vector(PyObject *obj, Py_ssize_t n, double *out) {
  if (PyList_CheckExact(obj) || PyTuple_CheckExact(obj)) {
    if (PySequence_Fast_GET_SIZE(obj) != n) return false;
    PyObject **items = PySequence_Fast_ITEMS(obj);
    for (Py_ssize_t k = 0; k < n; ++k) {
      PyObject *item = items[k];
      if (PyFloat_CheckExact(item)) {
        out[k] = PyFloat_AS_DOUBLE(item);
      } else if (PyLong_CheckExact(item)) {
        out[k] = PyLong_AsDouble(item);
        if (out[k] == -1.0 && PyErr_Occurred()) {
          PyErr_Clear();
          return false;
        }
      } else {
        return false;
      }
    }
    return true;
  }
  if (numpy_fields_ok && Py_TYPE(obj) == ndarray_type) {
    const NumpyArrayFields *a = reinterpret_cast<const NumpyArrayFields *>(obj);
    if (a->descr == float64_descr) {
      if (a->nd != 1 || a->dimensions[0] != n) return false;
      for (Py_ssize_t k = 0; k < n; ++k)
        std::memcpy(out + k, a->data + k * a->strides[0], sizeof(double));
      return true;
    }
  }
  if (!PyObject_CheckBuffer(obj)) return false;
  Py_buffer view;
  if (PyObject_GetBuffer(obj, &view, PyBUF_RECORDS_RO) != 0) {
    PyErr_Clear();
    return false;
  }
  bool ok = view.ndim == 1 && view.shape[0] == n && view.itemsize == sizeof(double) &&
            is_native_double(view.format);
  if (ok) {
    const char *p = static_cast<const char *>(view.buf);
    for (Py_ssize_t k = 0; k < n; ++k) std::memcpy(out + k, p + k * view.strides[0], sizeof(double));
  }
  PyBuffer_Release(&view);
  return ok;
}

// A C-contiguous, aligned buffer of `count` items of `itemsize` bytes
// (writable if asked), held for the duration of a pair call; None gives a
// null pointer (the status arrays, which the C pair calls accept as NULL).
class Array {
 public:
  Array(nb::handle obj, const char *name, long long count, Py_ssize_t itemsize, bool writable) {
    if (writable && obj.is_none() && std::strcmp(name, "status") == 0) return;
    int flags = PyBUF_C_CONTIGUOUS | (writable ? PyBUF_WRITABLE : 0);
    if (PyObject_GetBuffer(obj.ptr(), &view_, flags) != 0) throw nb::python_error();
    held_ = true;
    if (view_.len != count * itemsize ||
        reinterpret_cast<std::uintptr_t>(view_.buf) % alignof(double) != 0) {
      PyErr_Format(PyExc_ValueError,
                   "pw85._ext: %s: expected %lld aligned items of %zd bytes, got %zd bytes",
                   name, count, itemsize, view_.len);
      throw nb::python_error();
    }
  }
  Array(const Array &) = delete;
  Array &operator=(const Array &) = delete;
  ~Array() {
    if (held_) PyBuffer_Release(&view_);
  }
  template <class T>
  T *data() const {
    return static_cast<T *>(view_.buf);
  }

 private:
  Py_buffer view_{};
  bool held_ = false;
};

// The arguments the one-pair calls handle themselves: nthreads an int in
// [0, INT_MAX] (ignored for one pair), check True or False, method (below);
// anything else goes through the Python function.
bool plain_options(PyObject *nthreads, PyObject *check) {
  if (!PyLong_CheckExact(nthreads) || (check != Py_True && check != Py_False)) return false;
  int overflow;
  long long n = PyLong_AsLongLongAndOverflow(nthreads, &overflow);
  return overflow == 0 && n >= 0 && n <= INT_MAX;
}

// A PW85_METHOD_* from a pw85.Method or int, or a lower-case method name;
// -1 for anything else (the Python function converts or rejects it).
int method_of(PyObject *method) {
  static const char *const names[] = {"default", "brent", "newton", "rational", "zheng"};
  static_assert(PW85_METHOD_DEFAULT == 0 && PW85_METHOD_BRENT == 1 && PW85_METHOD_NEWTON == 2 &&
                    PW85_METHOD_RATIONAL == 3 && PW85_METHOD_ZHENG == 4,
                "names[] follows the PW85_METHOD_* values");
  if (PyUnicode_CheckExact(method)) {
    for (int k = 0; k < 5; ++k)
      if (PyUnicode_CompareWithASCIIString(method, names[k]) == 0) return k;
    return -1;
  }
  if (PyLong_Check(method) && !PyBool_Check(method)) {
    int overflow;
    long long v = PyLong_AsLongLongAndOverflow(method, &overflow);
    if (overflow == 0 && v >= 0 && v < 5) return static_cast<int>(v);
  }
  return -1;
}

nb::object overlap1(nb::handle r12, nb::handle q1, nb::handle q2, nb::handle nthreads,
                    nb::handle check) {
  double r[PW85_DIM], a[PW85_SYM], b[PW85_SYM];
  if (!plain_options(nthreads.ptr(), check.ptr()) || !read_vector(r12.ptr(), PW85_DIM, r) ||
      !read_vector(q1.ptr(), PW85_SYM, a) || !read_vector(q2.ptr(), PW85_SYM, b))
    return nb::none();
  int verdict;
  {
    nb::gil_scoped_release unlocked;
    verdict = pw85_overlap(r, a, b);
  }
  if (verdict < 0) return nb::none();
  nb::bool_ result(verdict == 1);
  if (check.ptr() == Py_True) return std::move(result);
  return nb::make_tuple(result, 0);
}

nb::object contact_function1(nb::handle r12, nb::handle q1, nb::handle q2, nb::handle method,
                             nb::handle nthreads, nb::handle check) {
  double r[PW85_DIM], a[PW85_SYM], b[PW85_SYM];
  int m = method_of(method.ptr());
  if (m < 0 || !plain_options(nthreads.ptr(), check.ptr()) ||
      !read_vector(r12.ptr(), PW85_DIM, r) || !read_vector(q1.ptr(), PW85_SYM, a) ||
      !read_vector(q2.ptr(), PW85_SYM, b))
    return nb::none();
  pw85_result res;
  int status;
  {
    nb::gil_scoped_release unlocked;
    status = pw85_contact_function_method(r, a, b, m, &res);
  }
  if (status != PW85_OK) return nb::none();
  nb::object mu2 = nb::steal(new_float64(res.mu2));
  if (!mu2.is_valid()) throw nb::python_error();
  nb::object lambda = nb::steal(new_float64(res.lambda));
  if (!lambda.is_valid()) throw nb::python_error();
  if (check.ptr() == Py_True) return nb::make_tuple(mu2, lambda);
  return nb::make_tuple(mu2, lambda, 0);
}

// The pair calls run the C pair call over chunks of this many pairs into a
// buffer of its outputs, then copy out the values the Python function
// returns: its outputs need 5 bytes (overlap) and 20 bytes (contact
// function) of new memory per pair instead of 9 and 60.
constexpr long long chunk_pairs = 32768;

int overlap_pairs(long long m, nb::handle r12, nb::handle q1, nb::handle q2,
                  nb::handle overlap, nb::handle status, int nthreads) {
  Array s(status, "status", m, sizeof(int), true), ov(overlap, "overlap", m, 1, true);
  int *st_out = s.data<int>();
  Array r(r12, "r12", m * PW85_DIM, sizeof(double), false);
  Array a(q1, "q1", m * PW85_SYM, sizeof(double), false);
  Array b(q2, "q2", m * PW85_SYM, sizeof(double), false);
  std::unique_ptr<int[]> verdicts(new (std::nothrow) int[std::min(m, chunk_pairs)]);
  if (!verdicts) throw std::bad_alloc();
  nb::gil_scoped_release unlocked;
  int ret = PW85_OK;
  bool *out = ov.data<bool>();
  for (long long k0 = 0; k0 < m; k0 += chunk_pairs) {
    long long len = std::min(chunk_pairs, m - k0);
    int st = pw85_overlap_pairs(len, r.data<const double>() + PW85_DIM * k0,
                                a.data<const double>() + PW85_SYM * k0,
                                b.data<const double>() + PW85_SYM * k0, verdicts.get(),
                                st_out ? st_out + k0 : nullptr, nthreads);
    if (ret == PW85_OK) ret = st;
    for (long long k = 0; k < len; ++k) out[k0 + k] = verdicts[k] > 0;
  }
  return ret;
}

int contact_function_pairs(long long m, nb::handle r12, nb::handle q1, nb::handle q2,
                           int method, nb::handle mu2, nb::handle lambda, nb::handle status,
                           int nthreads) {
  Array s(status, "status", m, sizeof(int), true);
  Array x(mu2, "mu2", m, sizeof(double), true), l(lambda, "lambda", m, sizeof(double), true);
  Array r(r12, "r12", m * PW85_DIM, sizeof(double), false);
  Array a(q1, "q1", m * PW85_SYM, sizeof(double), false);
  Array b(q2, "q2", m * PW85_SYM, sizeof(double), false);
  std::unique_ptr<pw85_result[]> res(new (std::nothrow) pw85_result[std::min(m, chunk_pairs)]);
  if (!res) throw std::bad_alloc();
  nb::gil_scoped_release unlocked;
  int ret = PW85_OK;
  double *mu2_out = x.data<double>(), *lambda_out = l.data<double>();
  int *st_out = s.data<int>();
  for (long long k0 = 0; k0 < m; k0 += chunk_pairs) {
    long long len = std::min(chunk_pairs, m - k0);
    int st = pw85_contact_function_pairs(len, r.data<const double>() + PW85_DIM * k0,
                                         a.data<const double>() + PW85_SYM * k0,
                                         b.data<const double>() + PW85_SYM * k0, method,
                                         res.get(), st_out ? st_out + k0 : nullptr, nthreads);
    if (ret == PW85_OK) ret = st;
    for (long long k = 0; k < len; ++k) {
      mu2_out[k0 + k] = res[k].mu2;
      lambda_out[k0 + k] = res[k].lambda;
    }
  }
  return ret;
}

}  // namespace

// Whether the NumpyArrayFields of a strided float64 view agree with what
// the buffer protocol reports for it.
bool check_numpy_fields(nb::handle numpy) {
  nb::object base = numpy.attr("arange")(12.0);
  nb::object view = base[nb::slice(1, 12, 4)];  // 3 elements, stride 32 bytes
  if (Py_TYPE(view.ptr()) != ndarray_type) return false;
  Py_buffer buffer;
  if (PyObject_GetBuffer(view.ptr(), &buffer, PyBUF_RECORDS_RO) != 0) {
    PyErr_Clear();
    return false;
  }
  const NumpyArrayFields *a = reinterpret_cast<const NumpyArrayFields *>(view.ptr());
  bool same = a->data == buffer.buf && a->nd == 1 && buffer.ndim == 1 &&
              a->dimensions[0] == 3 && buffer.shape[0] == 3 && a->strides[0] == 32 &&
              buffer.strides[0] == 32 && a->descr == float64_descr;
  PyBuffer_Release(&buffer);
  if (!same) return false;
  double v[3];
  for (int k = 0; k < 3; ++k) std::memcpy(v + k, a->data + k * a->strides[0], sizeof(double));
  return v[0] == 1.0 && v[1] == 5.0 && v[2] == 9.0;
}

NB_MODULE(_ext, m) {
  nb::module_ numpy = nb::module_::import_("numpy");
  ndarray_type = reinterpret_cast<PyTypeObject *>(numpy.attr("ndarray").inc_ref().ptr());
  float64_descr = numpy.attr("dtype")(numpy.attr("float64")).inc_ref().ptr();
  numpy_fields_ok = check_numpy_fields(numpy);
  m.attr("numpy_fields") = numpy_fields_ok;
  nb::object float64 = numpy.attr("float64");
  if (!PyType_Check(float64.ptr()) ||
      !PyType_IsSubtype(reinterpret_cast<PyTypeObject *>(float64.ptr()), &PyFloat_Type) ||
      reinterpret_cast<PyTypeObject *>(float64.ptr())->tp_basicsize != sizeof(PyFloatObject))
    throw nb::import_error("pw85._ext: numpy.float64 does not extend float as expected");
  float64_type = float64.release().ptr();  // kept for the life of the process
  m.doc() = "Compiled one-pair and per-pair calls of pw85 (internal; use pw85).";
  m.def("overlap1", &overlap1, nb::arg("r12").none(), nb::arg("q1").none(),
        nb::arg("q2").none(), nb::arg("nthreads").none(), nb::arg("check").none());
  m.def("contact_function1", &contact_function1, nb::arg("r12").none(), nb::arg("q1").none(),
        nb::arg("q2").none(), nb::arg("method").none(), nb::arg("nthreads").none(),
        nb::arg("check").none());
  m.def("overlap_pairs", &overlap_pairs, nb::arg("m"), nb::arg("r12"), nb::arg("q1"),
        nb::arg("q2"), nb::arg("overlap"), nb::arg("status").none(), nb::arg("nthreads"));
  m.def("contact_function_pairs", &contact_function_pairs, nb::arg("m"), nb::arg("r12"),
        nb::arg("q1"), nb::arg("q2"), nb::arg("method"), nb::arg("mu2"), nb::arg("lambda"),
        nb::arg("status").none(), nb::arg("nthreads"));
}
