#include "fem/fe_modal_damping.h"

#include <stdexcept>
#include <string>

namespace beamslider
{
  ModalDamping::ModalDamping(const dealii::SparseMatrix<double> &M, const FEModes &modes, const unsigned int n_kept,
                             const double damping_ratio)
  {
    if (n_kept > modes.shapes.size())
      throw std::invalid_argument("ModalDamping: " + std::to_string(n_kept) + " kept modes requested, only " +
                                  std::to_string(modes.shapes.size()) + " computed");
    for (unsigned int n = 0; n < n_kept; ++n)
      {
        dealii::Vector<double> v(M.m());
        M.vmult(v, modes.shapes[n]);
        M_phi.push_back(std::move(v));
        coefficients.push_back(2. * damping_ratio * modes.omega[n]);
      }
  }

  void ModalDamping::vmult(dealii::Vector<double> &dst, const dealii::Vector<double> &src) const
  {
    dst.reinit(src.size());
    for (unsigned int n = 0; n < M_phi.size(); ++n)
      dst.add(coefficients[n] * (M_phi[n] * src), M_phi[n]);
  }
} // namespace beamslider
