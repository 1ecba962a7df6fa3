// Model reader, part 5: the top-level "damping" of the dynamic analyses (core/model.hpp, Damping):
//   "damping": {"rayleigh": {"alpha": a, "beta": b}}   C = a M + b K
//   "damping": {"modal": zeta | [zeta_1, zeta_2, ...]}  a ratio per mode, the last for the rest
#include "core/errors.hpp"
#include "io/json_util.hpp"
#include "io/model_reader_parts.hpp"

namespace beamfea::reader {

using namespace json_in;

void read_damping(ReadState& s) {
  const json* d = field(s.doc, "damping");
  if (!d) return;
  const Pointer p("/damping");
  const Fields f(object(*d, p, "damping"), p, {"rayleigh", "modal"});
  const json* rayleigh = f.get("rayleigh");
  const json* modal = f.get("modal");
  if (rayleigh && modal) throw InputError(p, "damping: give \"rayleigh\" or \"modal\", not both");
  if (!rayleigh && !modal) throw InputError(p, "damping: expected \"rayleigh\" or \"modal\"");
  Damping& damping = s.model.damping;
  if (rayleigh) {
    const Pointer rp = child(p, "rayleigh");
    const Fields fr(object(*rayleigh, rp, "damping rayleigh"), rp, {"alpha", "beta"});
    damping.kind = Damping::Kind::Rayleigh;
    for (const char* key : {"alpha", "beta"}) {
      const json* v = fr.get(key);
      const double x = v ? number(*v, child(rp, key), What("damping rayleigh ", key)) : 0.0;
      if (x < 0.0) throw InputError(child(rp, key), std::string("damping rayleigh ") + key + " must not be negative");
      (key[0] == 'a' ? damping.alpha : damping.beta) = x;
    }
    return;
  }
  const Pointer mp = child(p, "modal");
  damping.kind = Damping::Kind::Modal;
  damping.modal = modal->is_array() ? numbers(*modal, mp, "damping modal") : std::vector<double>{number(*modal, mp, "damping modal")};
  if (damping.modal.empty()) throw InputError(mp, "damping modal: expected a ratio or a non-empty array of ratios");
  for (std::size_t k = 0; k < damping.modal.size(); ++k)
    if (damping.modal[k] < 0.0)
      throw InputError(modal->is_array() ? child(mp, k) : mp, "damping modal: a damping ratio must not be negative");
}

}  // namespace beamfea::reader
