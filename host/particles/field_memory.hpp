// A particle field's values as they lie in memory (ParticleSet::memory).
#pragma once
#include <cstddef>
#include <string>

namespace mfsd {

// Where a field's values lie, for views from outside the solver (the Python
// module's arrays): count elements of `components` scalars each, a `rows` x
// `rows` matrix when rows > 0; kind 'f' floating point, 'i' signed or 'u'
// unsigned integer of scalar_bytes. Fields of other structs (RKPM's
// operators) are not plain: no view.
struct FieldMemory {
  std::string name;
  void* data = nullptr;
  size_t count = 0;
  int components = 1;
  int rows = 0;
  char kind = 'f';
  int scalar_bytes = 8;
  bool plain = false;
  bool on_device = false;  // the backend's memory (a GPU's): copy with ParticleSet::bytes
};

}  // namespace mfsd
