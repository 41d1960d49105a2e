// The animation of a solid-derived reduced model on the solid, see
// solid_rom_animation.h.
#include "output/solid_rom_animation.h"

#include "io/output_file.h"
#include "fem/petsc_session.h"
#include "fem/solid_model.h"
#include "fem/solid_modes.h"
#include "output/solid_output.h"
#include "fem/solid_statics.h"

#include <deal.II/base/data_out_base.h>
#include <deal.II/base/function.h>
#include <deal.II/numerics/vector_tools_interpolate.h>

#include <iomanip>
#include <sstream>
#include <utility>
#include <vector>

namespace beamslider
{
  using namespace dealii;

  class SolidRomAnimation::Implementation
  {
  public:
    virtual ~Implementation() = default;
    virtual void write(const std::string &folder, const std::string &basename, double base_displacement,
                       const Eigen::VectorXd &q) = 0;
    virtual double section_deflection(const Eigen::VectorXd &q, double x) const = 0;

    std::string directory, name;
    std::vector<std::pair<double, std::string>> series; // (t [s], .pvtu file) per frame
  };

  namespace
  {
    template <int dim>
    class SolidFrames : public SolidRomAnimation::Implementation
    {
    public:
      SolidFrames(const Scene &scene, const unsigned int n_modes)
        : model(scene, MPI_COMM_SELF) // as the reduced model's build (fem/solid_reduced_model.cc)
        , statics(model)
      {
        const SolidModes modes = compute_solid_modes(model, n_modes);
        for (unsigned int n = 0; n < n_modes; ++n)
          {
            PETScWrappers::MPI::Vector phi;
            model.reinit_vector(phi);
            phi = modes.all[modes.bending[n]].vector;
            bending.push_back(std::move(phi));
          }
        // The base's rigid motion: the unit field e_z.
        Vector<double> ez(dim);
        ez[dim - 1] = 1;
        model.reinit_vector(unit_z);
        VectorTools::interpolate(model.mapping(), model.get_dof_handler(), Functions::ConstantFunction<dim>(ez),
                                 unit_z);
        model.reinit_vector(deflection);
        model.reinit_vector(displacement);
      }

      void write(const std::string &folder, const std::string &basename, const double base_displacement,
                 const Eigen::VectorXd &q) override
      {
        superpose(q, deflection);
        displacement = deflection;
        displacement.add(base_displacement, unit_z);
        write_solid_fields(model, {{"displacement", &displacement, 1.}, {"deflection", &deflection, 1.}}, folder,
                           basename);
      }

      double section_deflection(const Eigen::VectorXd &q, const double x) const override
      {
        PETScWrappers::MPI::Vector sum;
        model.reinit_vector(sum);
        superpose(q, sum);
        PETScWrappers::MPI::Vector ghosted;
        model.reinit_ghosted_vector(ghosted);
        ghosted = sum;
        return statics.section_deflection(ghosted, x);
      }

    private:
      // sum = Σ q_n φ_n (sum: a vector of the model's owned DoFs).
      void superpose(const Eigen::VectorXd &q, PETScWrappers::MPI::Vector &sum) const
      {
        if (static_cast<std::size_t>(q.size()) != bending.size())
          throw std::invalid_argument("solid animation: " + std::to_string(q.size()) + " modal coordinates for " +
                                      std::to_string(bending.size()) + " modes");
        sum = 0;
        for (unsigned int n = 0; n < bending.size(); ++n)
          sum.add(q[n], bending[n]);
      }

      const SolidModel<dim> model;
      const SolidStatics<dim> statics; // only its section averages
      std::vector<PETScWrappers::MPI::Vector> bending; // φ_n, mass-normalised
      PETScWrappers::MPI::Vector unit_z, deflection, displacement;
    };
  } // namespace

  SolidRomAnimation::SolidRomAnimation(const Scene &scene, const unsigned int n_modes, const std::string &directory,
                                       const std::string &name)
  {
    if (!scene.solid.enabled())
      throw InputError("an animation on the solid needs a scene with a Solid (Solid/Continuum = 3d or plane stress)");
    require_petsc();
    if (scene.solid.dimension() == 3)
      implementation = std::make_unique<SolidFrames<3>>(scene, n_modes);
    else
      implementation = std::make_unique<SolidFrames<2>>(scene, n_modes);
    implementation->directory = directory;
    implementation->name      = name;
  }

  SolidRomAnimation::~SolidRomAnimation()
  {
    try
      {
        finish();
      }
    catch (...)
      {}
  }

  void SolidRomAnimation::write(const double t, const double base_displacement, const Eigen::VectorXd &q)
  {
    std::ostringstream basename;
    basename << implementation->name << "_" << std::setw(5) << std::setfill('0') << n_frames();
    implementation->write(implementation->directory, basename.str(), base_displacement, q);
    implementation->series.emplace_back(t, basename.str() + ".pvtu");
    if (n_frames() % 25 == 0)
      finish();
  }

  void SolidRomAnimation::finish()
  {
    std::ostringstream record;
    DataOutBase::write_pvd_record(record, implementation->series);
    write_file_atomically(pvd_file(), record.str());
  }

  double SolidRomAnimation::section_deflection(const Eigen::VectorXd &q, const double x) const
  {
    return implementation->section_deflection(q, x);
  }

  unsigned int SolidRomAnimation::n_frames() const { return implementation->series.size(); }

  std::string SolidRomAnimation::pvd_file() const
  {
    return implementation->directory + "/" + implementation->name + ".pvd";
  }
} // namespace beamslider
