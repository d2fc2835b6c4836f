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

}  // namespace refmap
