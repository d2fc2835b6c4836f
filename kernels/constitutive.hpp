#pragma once
// The constitutive models of the solids, in one place. A model is a small stateless struct
// (its constants only) with inline functions of the left Cauchy-Green tensor b (eq. 2.9;
// kernels/constitutive_kinematics.hpp), used by the stress kernels (cell and face forms,
// kernels/solid_stress.hpp), the elastic-energy diagnostic and the time-step bound:
//   Sym2   stress(b)       stored solid stress: the Cauchy stress less an isotropic part
//                          (taken by the pressure), zero at rest
//   Sym2   strain(s)       b back from a stored stress (inverse of stress)
//   double energy(b)       strain-energy density (isochoric invariant, see the models)
//   double wave_modulus(b) tangent shear modulus G_t: shear-wave speed sqrt(G_t / rho_s)
//                          bounds the time step (section 4); 2 mu_s at rest
// The kernels are templates on the model, so their inner loops stay inlined and vectorised.
// Adding a model: one header kernels/constitutive_<name>.hpp, its include, enum value and
// case below, and its scene value in solver/components/solids_keys.cpp (for new constants: SolidSpec
// fields in solver/model/config.hpp, their keys and their reading in solver/components/solids_keys.cpp).
#include <concepts>
#include <utility>

#include "kernels/constitutive_actuation.hpp"
#include "kernels/constitutive_kinematics.hpp"
#include "kernels/constitutive_neo_hookean.hpp"
#include "kernels/constitutive_strain_stiffening.hpp"

namespace refmap {

template <class M>
concept ConstitutiveModel = requires(const M& m, const Sym2& t) {
  { m.stress(t) } -> std::same_as<Sym2>;
  { m.strain(t) } -> std::same_as<Sym2>;
  { m.energy(t) } -> std::convertible_to<double>;
  { m.wave_modulus(t) } -> std::convertible_to<double>;
};

static_assert(ConstitutiveModel<NeoHookean> && ConstitutiveModel<StrainStiffening>);
static_assert(ConstitutiveModel<Actuated<NeoHookean>> && ConstitutiveModel<Actuated<StrainStiffening>>);

enum class ConstitutiveLaw { NeoHookean, StrainStiffening };

/// Calls f(model) with the model of mat.model built from the material constants of `mat`
/// (a SolidSpec, solver/model/config.hpp: mu_s, the paper's mu_s and c1 of the stiffening law;
/// c3, the stiffening coefficient). The one switch on the law.
template <class Material, class F>
decltype(auto) with_constitutive_model(const Material& mat, F&& f) {
  switch (mat.model) {
    case ConstitutiveLaw::StrainStiffening: return std::forward<F>(f)(StrainStiffening(mat.mu_s, mat.c3));
    case ConstitutiveLaw::NeoHookean: break;
  }
  return std::forward<F>(f)(NeoHookean(mat.mu_s));
}

}  // namespace refmap
