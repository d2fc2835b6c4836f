// Scene-file names of the physics options (see solver/scene/option_names.hpp). The order of
// each list is the order of the choices in error messages and in scenes/README.md.
#include "solver/scene/option_names.hpp"

namespace refmap {

namespace {
template <class E, std::size_t N>
std::span<const OptionName<E>> span_of(const OptionName<E> (&a)[N]) {
  return {a, N};
}
}  // namespace

std::span<const OptionName<BcType>> option_names(BcType) {
  static const OptionName<BcType> n[] = {{BcType::NoSlip, "no_slip"},
                                         {BcType::FreeSlip, "free_slip"},
                                         {BcType::Periodic, "periodic"},
                                         {BcType::MovingWall, "moving_wall"},
                                         {BcType::Inflow, "inflow"},
                                         {BcType::Outflow, "outflow"}};
  return span_of(n);
}

std::span<const OptionName<FlowMode>> option_names(FlowMode) {
  static const OptionName<FlowMode> n[] = {{FlowMode::Solve, "solve"}, {FlowMode::Prescribed, "prescribed"}};
  return span_of(n);
}

std::span<const OptionName<FluxScheme>> option_names(FluxScheme) {
  static const OptionName<FluxScheme> n[] = {{FluxScheme::Central, "central"}, {FluxScheme::Superbee, "superbee"}};
  return span_of(n);
}

std::span<const OptionName<InitialKind>> option_names(InitialKind) {
  static const OptionName<InitialKind> n[] = {{InitialKind::Zero, "zero"},
                                              {InitialKind::Uniform, "uniform"},
                                              {InitialKind::TaylorGreen, "taylor_green"},
                                              {InitialKind::Expression, "expression"}};
  return span_of(n);
}

std::span<const OptionName<SolidVelocity>> option_names(SolidVelocity) {
  static const OptionName<SolidVelocity> n[] = {{SolidVelocity::Rigid, "rigid"}, {SolidVelocity::Fluid, "fluid"}};
  return span_of(n);
}

std::span<const OptionName<SolidMotion>> option_names(SolidMotion) {
  static const OptionName<SolidMotion> n[] = {{SolidMotion::Free, "free"},
                                              {SolidMotion::Fixed, "fixed"},
                                              {SolidMotion::Prescribed, "prescribed"},
                                              {SolidMotion::Pinned, "pinned"}};
  return span_of(n);
}

std::span<const OptionName<BodyForcing>> option_names(BodyForcing) {
  static const OptionName<BodyForcing> n[] = {{BodyForcing::Diffuse, "diffuse"},
                                              {BodyForcing::Interpolated, "interpolated"},
                                              {BodyForcing::Sharp, "sharp"}};
  return span_of(n);
}

std::span<const OptionName<ForcingInterpolation>> option_names(ForcingInterpolation) {
  static const OptionName<ForcingInterpolation> n[] = {{ForcingInterpolation::Linear, "linear"},
                                                       {ForcingInterpolation::Quadratic, "quadratic"}};
  return span_of(n);
}

std::span<const OptionName<ExtrapolationMethod>> option_names(ExtrapolationMethod) {
  static const OptionName<ExtrapolationMethod> n[] = {{ExtrapolationMethod::Lsq, "lsq"},
                                                      {ExtrapolationMethod::Pde, "pde"}};
  return span_of(n);
}

std::span<const OptionName<ConstitutiveLaw>> option_names(ConstitutiveLaw) {
  static const OptionName<ConstitutiveLaw> n[] = {{ConstitutiveLaw::NeoHookean, "neo_hookean"},
                                                  {ConstitutiveLaw::StrainStiffening, "strain_stiffening"}};
  return span_of(n);
}

std::span<const OptionName<StressForm>> option_names(StressForm) {
  static const OptionName<StressForm> n[] = {{StressForm::Cell, "cell"}, {StressForm::Face, "face"},
                                              {StressForm::Variational, "variational"}};
  return span_of(n);
}

std::span<const OptionName<StressBlend>> option_names(StressBlend) {
  static const OptionName<StressBlend> n[] = {{StressBlend::Volume, "volume"}, {StressBlend::Specific, "specific"}};
  return span_of(n);
}

std::span<const OptionName<JumpFlux>> option_names(JumpFlux) {
  static const OptionName<JumpFlux> n[] = {{JumpFlux::Superbee, "superbee"}, {JumpFlux::Same, "same"}};
  return span_of(n);
}

std::span<const OptionName<ViscousTime>> option_names(ViscousTime) {
  static const OptionName<ViscousTime> n[] = {{ViscousTime::Explicit, "explicit"}, {ViscousTime::Implicit, "implicit"}};
  return span_of(n);
}

std::span<const OptionName<Splitting>> option_names(Splitting) {
  static const OptionName<Splitting> n[] = {{Splitting::Split, "split"}, {Splitting::Increment, "increment"}};
  return span_of(n);
}

std::span<const OptionName<SolidStressTime>> option_names(SolidStressTime) {
  static const OptionName<SolidStressTime> n[] = {{SolidStressTime::Explicit, "explicit"},
                                                  {SolidStressTime::SemiImplicit, "semi_implicit"},
                                                  {SolidStressTime::UpperConvected, "upper_convected"}};
  return span_of(n);
}

std::span<const OptionName<ElasticCoupling>> option_names(ElasticCoupling) {
  static const OptionName<ElasticCoupling> n[] = {{ElasticCoupling::SymplecticEuler, "symplectic_euler"},
                                                  {ElasticCoupling::Verlet, "verlet"}};
  return span_of(n);
}

std::span<const OptionName<PicardForce>> option_names(PicardForce) {
  static const OptionName<PicardForce> n[] = {{PicardForce::New, "new"}, {PicardForce::Trapezoidal, "trapezoidal"}};
  return span_of(n);
}

std::span<const OptionName<XiFlux>> option_names(XiFlux) {
  static const OptionName<XiFlux> n[] = {
      {XiFlux::Central, "central"}, {XiFlux::Superbee, "superbee"}, {XiFlux::VanLeer, "vanleer"},
      {XiFlux::Minmod, "minmod"}};
  return span_of(n);
}

std::span<const OptionName<XiVelocity>> option_names(XiVelocity) {
  static const OptionName<XiVelocity> n[] = {{XiVelocity::Face, "face"}, {XiVelocity::Cell, "cell"}};
  return span_of(n);
}

}  // namespace refmap
