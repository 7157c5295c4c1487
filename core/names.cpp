#include "core/case.hpp"
#include "core/model.hpp"
#include "core/result.hpp"

namespace glrc {

std::vector<std::string> component_names(const Case& c) {
  static const char* kSuffix[] = {"x", "y", "z", "w"};
  std::vector<std::string> names;
  for (const auto& v : c.varyings)
    for (int i = 0; i < v.size; ++i)
      names.push_back(v.name + "." + kSuffix[i]);
  return names;
}

std::string channel_name(const Case& c, Channel ch) {
  return ch.is_depth() ? "depth" : component_names(c).at(size_t(ch.component()));
}

std::vector<int> component_varying(const Case& c) {
  std::vector<int> owner;
  for (size_t k = 0; k < c.varyings.size(); ++k)
    for (int i = 0; i < c.varyings[k].size; ++i)
      owner.push_back(int(k));
  return owner;
}

VaryingComponent varying_component(const Case& c, int k) {
  size_t v = 0;
  while (v + 1 < c.varyings.size() && k >= c.varyings[v].size)
    k -= c.varyings[v++].size;
  return {v, k};
}

// The tables' names are string literals, so their data() ends in a NUL.
const char* to_string(TieBreak t) {
  return name_of(t).data();
}

const char* to_string(Planes p) {
  return name_of(p).data();
}

std::string Model::describe() const {
  return "subpixel_bits=" + std::to_string(subpixel_bits) + " planes=" + to_string(planes) +
         " tie=" + to_string(tie_break);
}

const char* to_string(ToleranceMode m) {
  return name_of(m).data();
}

const char* to_string(Status s) {
  return name_of(s).data();
}

std::optional<Status> status_from_string(std::string_view s) {
  return from_name<Status>(s);
}

}  // namespace glrc
