#pragma once
// Linear springs with no strength: the joint never fails and carries tension. A second law that
// shares nothing with Mohr-Coulomb but the LawGroup interface; useful for elastic verification.
#include <algorithm>
#include <array>
#include <limits>

#include "vorodec/laws/contact_law.hpp"

namespace vorodec::laws {

struct LinearElastic {
  static constexpr std::string_view name = "linear_elastic";
  struct Params {
    model::Distribution jkn, jks;
  };
  struct Props {
    double kn, ks;  // N/m
  };
  static constexpr std::array<std::string_view, 2> property_names{"kn [N/m]", "ks [N/m]"};
  struct State {
    double fs;      // N
    double origin;  // m, gap at which the normal spring is unloaded (NewContact)
  };

  static Params params_from(const LawParams& p) { return {p.at("jkn"), p.at("jks")}; }
  static Props sample(const Params& p, std::uint64_t seed, const NewContact& c) {
    return {p.jkn.sample(seed, c.id, 0) * c.length, p.jks.sample(seed, c.id, 1) * c.length};
  }
  static State initial_state(const NewContact& c) { return {0.0, c.spring_origin}; }
  static double max_stiffness(const Props& p) { return std::max(p.kn, p.ks); }
  static double strain_energy(const Props& p, double fn, double fs) {
    return 0.5 * (fn * fn / p.kn + (p.ks > 0.0 ? fs * fs / p.ks : 0.0));
  }
  static LinearSprings linear_springs(const Props& p, const State&) { return {p.kn, p.ks, false}; }
  static double elastic_reach(const Props&, const State&, double, double, double, double) {
    return std::numeric_limits<double>::infinity();
  }
  static void preload(const Props& p, State& st, double gap, double fn, double fs) {
    st.origin = gap + fn / p.kn;
    st.fs = fs;
  }
  static LawResult evaluate(const ContactKinematics& k, const Props& p, State& st) {
    st.fs -= p.ks * k.du_s;
    return {-p.kn * (k.gap - st.origin), st.fs, ContactEvent::none, true};
  }
};

}  // namespace vorodec::laws
