#pragma once
// Initial level sets of solids: phi0(X) in the reference configuration, so that
// phi(x, t) = phi0(xi(x, t)) (Jain & Mani 2017, eq. 3.2). Negative inside the solid.
// phi0 is the exact signed distance for every analytic shape here (Circle, Ellipse,
// RoundedRectangle, ZalesakDisk); Tabulated interpolates a sampled phi0 bilinearly
// (section 3.2.1 of the paper), which is only as much a distance as the data is.
//
// Angles are in radians, counter-clockwise, the shape being rotated about its centre.
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

#include "solver/model/shape_params.hpp"

namespace refmap {

/// Axis-aligned extent of a solid in its reference configuration (where phi0 <= 0).
struct BoundingBox {
  double xmin = 0, ymin = 0, xmax = 0, ymax = 0;
};

class Shape {
 public:
  virtual ~Shape();
  /// Level set in the reference configuration: < 0 inside, > 0 outside.
  virtual double phi0(double X, double Y) const = 0;
  /// Reference-configuration extent of the solid (phi0 <= 0 lies inside it).
  virtual BoundingBox bbox() const = 0;
  /// One-line human-readable description with the parameters.
  virtual std::string describe() const;
};

class Circle final : public Shape {
 public:
  Circle(double cx, double cy, double r);
  double phi0(double X, double Y) const override;
  BoundingBox bbox() const override;
  std::string describe() const override;

 private:
  double cx_, cy_, r_;
};

/// Ellipse with semi-axes a (along the rotated x axis) and b. phi0 is the exact signed
/// distance, from the closest point computed by a safeguarded Newton iteration on
/// Eberly's one-dimensional root function (accurate to round-off).
class Ellipse final : public Shape {
 public:
  Ellipse(double cx, double cy, double a, double b, double angle = 0.0);
  double phi0(double X, double Y) const override;
  BoundingBox bbox() const override;
  std::string describe() const override;
  /// Closest point on the ellipse to (X, Y) (global coordinates).
  void closest_point(double X, double Y, double& xc, double& yc) const;

 private:
  double cx_, cy_, a_, b_, angle_, c_, s_;
};

/// Rectangle of half-width hw, half-height hh with corners rounded by radius rc
/// (0 <= rc <= min(hw, hh); rc = 0 gives sharp corners). Exact signed distance.
class RoundedRectangle final : public Shape {
 public:
  RoundedRectangle(double cx, double cy, double hw, double hh, double rc, double angle = 0.0);
  double phi0(double X, double Y) const override;
  BoundingBox bbox() const override;
  std::string describe() const override;

 private:
  double cx_, cy_, hw_, hh_, rc_, angle_, c_, s_;
};

/// Zalesak's slotted disk: disk of radius r centred at (cx, cy), minus the slot
/// |x' - cx| <= slot_half_width, y' <= slot_top cut from the bottom of the disk, where
/// (x', y') are coordinates in the frame rotated by `angle` about the centre (slot_top
/// is the y of the slot's top edge in the unrotated configuration). The standard
/// unit-square form is ZalesakDisk(0.5, 0.75, 0.15, 0.025, 0.85). phi0 is the exact
/// signed distance to the boundary (arc + two walls + top of the slot).
/// Requires 0 < slot_half_width < r and cy - sqrt(r^2 - w^2) < slot_top < cy + sqrt(r^2 - w^2).
class ZalesakDisk final : public Shape {
 public:
  ZalesakDisk(double cx, double cy, double r, double slot_half_width, double slot_top,
              double angle = 0.0);
  double phi0(double X, double Y) const override;
  BoundingBox bbox() const override;
  std::string describe() const override;

 private:
  double cx_, cy_, r_, w_, top_, angle_, c_, s_;
  double yb_;  ///< y (relative to the centre) where the slot walls meet the circle
};

/// A phi0 sampled on a regular grid, interpolated bilinearly.
///
/// File format (plain text, whitespace-separated; blank lines and lines starting with
/// '#' are ignored):
///     nx ny x0 y0 dx
///     v(0,0)    v(1,0)    ... v(nx-1,0)        <- the row at y = y0
///     v(0,1)    ...                            <- y = y0 + dx
///     ...
///     v(0,ny-1) ...       ... v(nx-1,ny-1)     <- y = y0 + (ny-1) dx
/// Sample v(i, j) sits at (x0 + i dx, y0 + j dx); nx, ny >= 2, dx > 0; exactly ny rows
/// of exactly nx finite numbers. Outside the sampled rectangle the nearest boundary
/// value is used (constant extension), so the table must enclose the solid (its border
/// values should be positive).
class Tabulated final : public Shape {
 public:
  /// Reads the file; throws std::runtime_error naming the file and line on bad input.
  explicit Tabulated(const std::string& path);
  /// Parses a stream; `name` is used in error messages.
  Tabulated(std::istream& in, const std::string& name);
  /// From data in memory: values[j * nx + i] = v(i, j).
  Tabulated(int nx, int ny, double x0, double y0, double dx, std::vector<double> values);

  double phi0(double X, double Y) const override;
  BoundingBox bbox() const override;
  std::string describe() const override;
  int nx() const { return nx_; }
  int ny() const { return ny_; }

 private:
  void parse(std::istream& in, const std::string& name);
  void finish();
  int nx_ = 0, ny_ = 0;
  double x0_ = 0, y0_ = 0, dx_ = 1;
  std::vector<double> v_;
  std::string source_;
  BoundingBox bbox_;
};

/// Builds the shape; throws std::invalid_argument on invalid
/// parameters, std::runtime_error on an unreadable/malformed tabulated file.
std::unique_ptr<Shape> make_shape(const ShapeParams& p);

}  // namespace refmap
