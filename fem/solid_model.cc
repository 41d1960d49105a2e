#include "fem/solid_model.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/work_stream.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/base/mpi.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/distributed/fully_distributed_tria.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/mapping_fe.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/filtered_iterator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria_description.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/numerics/vector_tools.h>

#include <algorithm>
#include <array>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace beamslider
{
  using namespace dealii;

  template <int dim>
  SolidModel<dim>::SolidModel(const Scene &scene, MPI_Comm communicator)
    : mpi_communicator(communicator)
    , beam(scene.beam)
    , from_mesh(scene.solid.from_mesh())
    , is_simplex(false)
  {
    if (!scene.solid.enabled() || scene.solid.dimension() != dim)
      throw std::invalid_argument("SolidModel<" + std::to_string(dim) + ">: the scene's Solid/Continuum is '" +
                                  scene.solid.continuum + "'");
    if (from_mesh)
      {
        // Every rank reads the whole mesh file (its errors then reach every
        // rank alike), METIS partitions it, each rank keeps its part.
        Triangulation<dim> serial;
        groups     = make_solid_mesh(scene, serial);
        is_simplex = serial.all_reference_cells_are_simplex();
        GridTools::partition_triangulation(Utilities::MPI::n_mpi_processes(communicator), serial);
        auto distributed = std::make_unique<parallel::fullydistributed::Triangulation<dim>>(communicator);
        distributed->create_triangulation(
          TriangulationDescription::Utilities::create_description_from_triangulation(serial, communicator));
        triangulation = std::move(distributed);
      }
    else
      {
        auto distributed = std::make_unique<parallel::distributed::Triangulation<dim>>(communicator);
        groups           = make_solid_mesh(scene, *distributed);
        triangulation    = std::move(distributed);
      }

    const unsigned int p = scene.solid.degree;
    if (is_simplex)
      {
        fe              = std::make_unique<FESystem<dim>>(FE_SimplexP<dim>(p), dim);
        cell_mapping    = std::make_unique<MappingFE<dim>>(FE_SimplexP<dim>(1));
        cell_quadrature = QGaussSimplex<dim>(p + 1);
        face_rule       = QGaussSimplex<dim - 1>(p + 1);
      }
    else
      {
        fe              = std::make_unique<FESystem<dim>>(FE_Q<dim>(p), dim);
        cell_mapping    = std::make_unique<MappingQ<dim>>(1);
        cell_quadrature = QGauss<dim>(p + 1);
        face_rule       = QGauss<dim - 1>(p + 1);
      }

    dof_handler.reinit(*triangulation);
    dof_handler.distribute_dofs(*fe);
    owned_dofs = dof_handler.locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(dof_handler, relevant_dofs);

    if (scene.supports.elastic())
      {
        plate_axial_stiffness      = scene.supports.axial_spring_per_end();
        plate_rotational_stiffness = scene.supports.rotational_stiffness;
        make_end_plates(scene.solid.clamped_boundaries);
      }
    else
      {
        clamp_constraints.reinit(relevant_dofs);
        DoFTools::make_hanging_node_constraints(dof_handler, clamp_constraints);
        for (const types::boundary_id face : groups.clamped)
          DoFTools::make_zero_boundary_constraints(dof_handler, face, clamp_constraints);
      }
    clamp_constraints.close();

    sparsity.reinit(relevant_dofs.size(), relevant_dofs.size(), relevant_dofs);
    DoFTools::make_sparsity_pattern(dof_handler, sparsity, clamp_constraints, false);
    SparsityTools::distribute_sparsity_pattern(sparsity, owned_dofs, mpi_communicator, relevant_dofs);
  }

  template <int dim>
  void SolidModel<dim>::make_end_plates(const std::vector<std::string> &group_names)
  {
    // Every DoF this rank sees (owned and ghost cells) on the two end faces
    // (the mesh's clamped groups, which elastic supports turn into plates),
    // with its support point and component.
    const FESystem<dim> &fe = *this->fe;
    const double h          = beam.thickness, tol = 1e-9 * h;
    struct FaceDof
    {
      types::global_dof_index index;
      unsigned int component;
      Point<dim> point;
    };
    std::array<std::vector<FaceDof>, 2> face_dofs;
    std::vector<types::global_dof_index> indices(fe.n_dofs_per_face());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (!cell->is_artificial())
        for (const unsigned int f : cell->face_indices())
          if (const auto end = std::find(groups.clamped.begin(), groups.clamped.end(), cell->face(f)->boundary_id());
              cell->face(f)->at_boundary() && end != groups.clamped.end())
            {
              const Quadrature<dim - 1> support(fe.get_unit_face_support_points(f));
              FEFaceValues<dim> points(*cell_mapping, fe, support, update_quadrature_points);
              points.reinit(cell, f);
              cell->face(f)->get_dof_indices(indices);
              for (unsigned int i = 0; i < indices.size(); ++i)
                face_dofs[end - groups.clamped.begin()].push_back(
                  {indices[i], fe.face_system_to_component_index(i, f).first, points.quadrature_point(i)});
            }

    // A mesh file's clamped groups must be the strip's two end faces: the
    // plates are planes x = 0 and x = L spanning the section |z| ≤ h/2.
    // Checked on every rank alike (reductions), so that all of them throw.
    if (groups.clamped.size() != 2)
      throw InputError("Parameter 'Supports/Type' = elastic: the solid needs exactly two clamped groups, the end "
                       "faces x = 0 and x = L that become the supports' rigid plates ('Solid/Clamped boundaries' "
                       "names " + std::to_string(groups.clamped.size()) + ")");
    for (unsigned int end = 0; end < 2; ++end)
      {
        double x_min = std::numeric_limits<double>::max(), x_max = -x_min, z_max = 0;
        for (const FaceDof &d : face_dofs[end])
          {
            x_min = std::min(x_min, d.point[0]);
            x_max = std::max(x_max, d.point[0]);
            z_max = std::max(z_max, std::abs(d.point[dim - 1]));
          }
        x_min = Utilities::MPI::min(x_min, mpi_communicator);
        x_max = Utilities::MPI::max(x_max, mpi_communicator);
        z_max = Utilities::MPI::max(z_max, mpi_communicator);
        const double L = beam.length, x_tol = 1e-9 * L;
        const bool at_an_end = std::abs(x_min) < x_tol || std::abs(x_max - L) < x_tol;
        if (x_max - x_min > x_tol || !at_an_end || z_max > 0.5 * h + tol)
          {
            std::ostringstream message;
            message << "Parameter 'Supports/Type' = elastic: the clamped group '"
                    << (end < group_names.size() ? group_names[end] : std::to_string(groups.clamped[end]))
                    << "' is not an end face of the strip (its nodes span x = " << x_min << " ... " << x_max
                    << " m, |z| up to " << z_max << " m); the elastic supports need the faces x = 0 and x = L = "
                    << L << " m within |z| <= h/2 = " << 0.5 * h << " m (or use Supports/Type = clamped)";
            throw InputError(message.str());
          }
      }

    // The plate's nodes: u_x at z = ∓h/2 nearest y = 0, the same on every
    // rank (the best candidate of each rank, gathered, the smallest |y|
    // then the smallest index).
    auto master = [&](const std::vector<FaceDof> &dofs, const double z) {
      std::pair<double, types::global_dof_index> best{std::numeric_limits<double>::max(), 0};
      for (const FaceDof &d : dofs)
        if (d.component == 0 && std::abs(d.point[dim - 1] - z) < tol)
          best = std::min(best, std::make_pair(dim == 3 ? std::abs(d.point[1]) : 0., d.index));
      const auto all  = Utilities::MPI::all_gather(mpi_communicator, best);
      const auto most = std::min_element(all.begin(), all.end());
      if (most->first == std::numeric_limits<double>::max())
        throw InputError("Parameter 'Supports/Type' = elastic: an end face of the solid has no node at z = " +
                         std::to_string(z) + " m, where the supports' plate is held (the mesh must reach "
                         "z = ±h/2 at both ends)");
      return most->second;
    };
    for (unsigned int end = 0; end < 2; ++end)
      plates.push_back({master(face_dofs[end], -0.5 * h), master(face_dofs[end], 0.5 * h)});

    // Ghost entries for the plate's DoFs on every rank: each rank's
    // constrained u_x read them, and the springs act on them.
    for (const EndPlate &p : plates)
      {
        relevant_dofs.add_index(p.bottom);
        relevant_dofs.add_index(p.top);
      }
    clamp_constraints.reinit(relevant_dofs);
    DoFTools::make_hanging_node_constraints(dof_handler, clamp_constraints);
    for (unsigned int end = 0; end < 2; ++end)
      for (const FaceDof &d : face_dofs[end])
        {
          if (clamp_constraints.is_constrained(d.index) || d.index == plates[end].bottom || d.index == plates[end].top)
            continue;
          clamp_constraints.add_line(d.index);
          if (d.component != 0)
            continue; // u_y = u_z = 0
          // u_x = U − θ z = (½ − z/h) u_b + (½ + z/h) u_t: u_b at z = −h/2, u_t at h/2
          const double z = d.point[dim - 1];
          if (std::abs(0.5 - z / h) > 1e-12)
            clamp_constraints.add_entry(d.index, plates[end].bottom, 0.5 - z / h);
          if (std::abs(0.5 + z / h) > 1e-12)
            clamp_constraints.add_entry(d.index, plates[end].top, 0.5 + z / h);
        }
  }

  template <int dim>
  double SolidModel<dim>::support_spring_product(const PETScWrappers::MPI::Vector &a,
                                                 const PETScWrappers::MPI::Vector &b) const
  {
    // ½ (2k_t) U² + ½ k_r θ² with U = (u_b + u_t)/2, θ = (u_b − u_t)/h.
    double product = 0;
    const double h = beam.thickness;
    for (const EndPlate &p : plates)
      {
        const double Ua = 0.5 * (a(p.bottom) + a(p.top)), Ub = 0.5 * (b(p.bottom) + b(p.top));
        const double ta = (a(p.bottom) - a(p.top)) / h, tb = (b(p.bottom) - b(p.top)) / h;
        product += plate_axial_stiffness * Ua * Ub + plate_rotational_stiffness * ta * tb;
      }
    return product;
  }

  template <int dim>
  void SolidModel<dim>::add_support_springs(const PETScWrappers::MPI::Vector &u, PETScWrappers::MPI::Vector *f,
                                            PETScWrappers::MPI::SparseMatrix *K_t) const
  {
    // The springs' stiffness on (u_b, u_t): (k_a/4) [1 1; 1 1] + (k_r/h²) [1 −1; −1 1].
    const double h = beam.thickness;
    const double a = 0.25 * plate_axial_stiffness, r = plate_rotational_stiffness / (h * h);
    for (const EndPlate &p : plates)
      {
        const types::global_dof_index dofs[2] = {p.bottom, p.top};
        const double k[2][2] = {{a + r, a - r}, {a - r, a + r}};
        for (unsigned int i = 0; i < 2; ++i)
          if (owned_dofs.is_element(dofs[i]))
            for (unsigned int j = 0; j < 2; ++j)
              {
                if (K_t)
                  K_t->add(dofs[i], dofs[j], k[i][j]);
                if (f)
                  (*f)(dofs[i]) += k[i][j] * u(dofs[j]);
              }
      }
    if (f)
      f->compress(VectorOperation::add);
    if (K_t)
      K_t->compress(VectorOperation::add);
  }

  template <int dim>
  std::string SolidModel<dim>::element_name() const
  {
    return std::string(is_simplex ? "FE_SimplexP(" : "FE_Q(") + std::to_string(fe->degree) + ")";
  }

  template <int dim>
  void SolidModel<dim>::reinit_matrix(PETScWrappers::MPI::SparseMatrix &A) const
  {
    A.reinit(owned_dofs, owned_dofs, sparsity, mpi_communicator);
  }

  template <int dim>
  void SolidModel<dim>::reinit_vector(PETScWrappers::MPI::Vector &v) const
  {
    v.reinit(owned_dofs, mpi_communicator);
  }

  template <int dim>
  void SolidModel<dim>::reinit_ghosted_vector(PETScWrappers::MPI::Vector &v) const
  {
    v.reinit(owned_dofs, relevant_dofs, mpi_communicator);
  }

  namespace
  {
    // The assembly loops in the style of deal.II's step-44: a cell worker
    // fills a CellCopy from the FEValues and work arrays of a scratch
    // object, a copier adds it to the global matrix and vector. With the
    // thread limit at 1 (main), WorkStream runs the cells in order on one
    // scratch object, so the global sums are the plain loop's.
    template <int dim>
    struct CellScratch
    {
      CellScratch(const Mapping<dim> &mapping, const FiniteElement<dim> &fe, const Quadrature<dim> &quadrature,
                  const UpdateFlags flags)
        : fe_values(mapping, fe, quadrature, flags)
      {}
      // FEValues cannot be copied: WorkStream's copies build their own.
      CellScratch(const CellScratch &other)
        : fe_values(other.fe_values.get_mapping(), other.fe_values.get_fe(), other.fe_values.get_quadrature(),
                    other.fe_values.get_update_flags())
      {}

      FEValues<dim> fe_values;
    };

    // A cell's matrix and/or vector and its DoFs.
    struct CellCopy
    {
      explicit CellCopy(const unsigned int n)
        : matrix(n, n)
        , vector(n)
        , dofs(n)
      {}

      FullMatrix<double> matrix;
      Vector<double> vector;
      std::vector<types::global_dof_index> dofs;
    };

    // The internal force's work arrays. A shape function φ_i of the vector
    // FE_Q is e_c ⊗ N_i in one component c = c_i, so ∇φ_i = e_c ⊗ ∇N_i: per
    // i we keep c_i and g_i = ∇N_i, and δE_i = sym(Fᵀ∇φ_i) = sym(a_i ⊗ g_i)
    // with a_i = Fᵀ e_c (row c of F), ∇φ_iᵀ∇φ_j = δ_{c_i c_j} g_i ⊗ g_j. The
    // tangent's double contraction needs no tensors: with F g_j (per j) and
    // F Fᵀ (per point),
    //   tr δE_i = (F g_i)_{c_i},  S : δE_i = a_i · S g_i,
    //   δE_i : δE_j = ½ [(F Fᵀ)_{c_i c_j} g_i·g_j + (F g_j)_{c_i} (F g_i)_{c_j}].
    template <int dim>
    struct StrainScratch : CellScratch<dim>
    {
      StrainScratch(const Mapping<dim> &mapping, const FiniteElement<dim> &fe, const Quadrature<dim> &quadrature)
        : CellScratch<dim>(mapping, fe, quadrature, update_gradients | update_JxW_values)
        , grad_u(quadrature.size())
        , component(fe.n_dofs_per_cell())
        , g(fe.n_dofs_per_cell())
        , Sg(fe.n_dofs_per_cell())
        , Fg(fe.n_dofs_per_cell())
        , trace_dE(fe.n_dofs_per_cell())
      {
        for (unsigned int i = 0; i < component.size(); ++i)
          component[i] = fe.system_to_component_index(i).first;
      }

      std::vector<Tensor<2, dim>> grad_u;
      std::vector<unsigned int> component;
      std::vector<Tensor<1, dim>> g, Sg, Fg;
      std::vector<double> trace_dE;
    };

    // ∫ ρ v·w dV on one cell.
    template <int dim>
    void mass_on_cell(const SolidModel<dim> &model, const typename DoFHandler<dim>::active_cell_iterator &cell,
                      CellScratch<dim> &scratch, CellCopy &copy)
    {
      FEValues<dim> &fe_values = scratch.fe_values;
      const FiniteElement<dim> &fe = fe_values.get_fe();
      const unsigned int n = fe.n_dofs_per_cell();
      FullMatrix<double> &cell_matrix = copy.matrix;
      const double rho = model.material(cell->material_id()).density * model.out_of_plane_thickness();
      fe_values.reinit(cell);
      cell_matrix = 0;
      for (const unsigned int q : fe_values.quadrature_point_indices())
        for (unsigned int i = 0; i < n; ++i)
          {
            const unsigned int ci = fe.system_to_component_index(i).first;
            for (unsigned int j = 0; j < n; ++j)
              if (fe.system_to_component_index(j).first == ci)
                cell_matrix(i, j) += rho * fe_values.shape_value(i, q) * fe_values.shape_value(j, q) * fe_values.JxW(q);
          }
      cell->get_dof_indices(copy.dofs);
    }

    // f(u) on one cell, and K_t(u) if `tangent` (scratch's comment says how).
    template <int dim>
    void internal_force_on_cell(const SolidModel<dim> &model, const PETScWrappers::MPI::Vector &u,
                                const bool tangent, const typename DoFHandler<dim>::active_cell_iterator &cell,
                                StrainScratch<dim> &scratch, CellCopy &copy)
    {
      FEValues<dim> &fe_values = scratch.fe_values;
      const std::vector<unsigned int> &component = scratch.component;
      std::vector<Tensor<1, dim>> &g = scratch.g, &Sg = scratch.Sg, &Fg = scratch.Fg;
      std::vector<double> &trace_dE = scratch.trace_dE;
      FullMatrix<double> &cell_matrix = copy.matrix;
      Vector<double> &cell_force = copy.vector;
      const unsigned int n = component.size();
      const Tensor<2, dim> I = unit_symmetric_tensor<dim>();
      const double factor    = model.out_of_plane_thickness();

      const SolidMaterial &law = model.material(cell->material_id());
      const double lambda = law.lambda, mu = law.mu;
      fe_values.reinit(cell);
      fe_values[FEValuesExtractors::Vector(0)].get_function_gradients(u, scratch.grad_u);
      cell_matrix = 0;
      cell_force  = 0;
      for (const unsigned int q : fe_values.quadrature_point_indices())
        {
          const Tensor<2, dim> F  = I + scratch.grad_u[q];
          const Tensor<2, dim> E  = 0.5 * (transpose(F) * F - I);
          const Tensor<2, dim> S  = lambda * trace(E) * I + 2 * mu * E;
          const double JxW        = fe_values.JxW(q) * factor;
          for (unsigned int i = 0; i < n; ++i)
            {
              g[i] = fe_values.shape_grad_component(i, q, component[i]);
              Tensor<1, dim> a_i; // Fᵀ e_c: row c of F
              for (unsigned int a = 0; a < dim; ++a)
                a_i[a] = F[component[i]][a];
              Sg[i] = S * g[i];
              cell_force(i) += (a_i * Sg[i]) * JxW; // S : δE_i (S symmetric)
              if (tangent)
                {
                  Fg[i]       = F * g[i];
                  trace_dE[i] = Fg[i][component[i]];
                }
            }
          // K_t is the Hessian of the strain energy, so symmetric: the
          // upper triangle here, the lower one copied after the loop
          // over quadrature points (half the work of the costliest loop
          // of a solid's statics and ICE; `verify --section 8`).
          if (tangent)
            {
              const Tensor<2, dim> FFt = F * transpose(F);
              for (unsigned int i = 0; i < n; ++i)
                {
                  const unsigned int c_i = component[i];
                  for (unsigned int j = i; j < n; ++j)
                    {
                      // δE_i : C : δE_j + S : (∇φ_iᵀ ∇φ_j), C = λ I⊗I + 2μ 𝕀
                      const unsigned int c_j = component[j];
                      double k_ij = lambda * trace_dE[i] * trace_dE[j] +
                                    mu * (FFt[c_i][c_j] * (g[i] * g[j]) + Fg[j][c_i] * Fg[i][c_j]);
                      if (c_i == c_j)
                        k_ij += g[i] * Sg[j];
                      cell_matrix(i, j) += k_ij * JxW;
                    }
                }
            }
        }
      if (tangent)
        for (unsigned int i = 1; i < n; ++i)
          for (unsigned int j = 0; j < i; ++j)
            cell_matrix(i, j) = cell_matrix(j, i);
      cell->get_dof_indices(copy.dofs);
    }
  } // namespace

  template <int dim>
  void SolidModel<dim>::assemble_mass_matrix(PETScWrappers::MPI::SparseMatrix &M) const
  {
    reinit_matrix(M);
    using CellIterator = typename DoFHandler<dim>::active_cell_iterator;
    WorkStream::run(
      filter_iterators(dof_handler.active_cell_iterators(), IteratorFilters::LocallyOwnedCell()),
      [this](const CellIterator &cell, CellScratch<dim> &scratch, CellCopy &copy) {
        mass_on_cell(*this, cell, scratch, copy);
      },
      [this, &M](const CellCopy &copy) { clamp_constraints.distribute_local_to_global(copy.matrix, copy.dofs, M); },
      CellScratch<dim>(*cell_mapping, *fe, cell_quadrature, update_values | update_JxW_values),
      CellCopy(fe->n_dofs_per_cell()));
    M.compress(VectorOperation::add);
  }

  template <int dim>
  void SolidModel<dim>::assemble_internal_force(const PETScWrappers::MPI::Vector &u, PETScWrappers::MPI::Vector *f,
                                                PETScWrappers::MPI::SparseMatrix *K_t) const
  {
    if (f)
      {
        reinit_vector(*f);
        *f = 0;
      }
    // A matrix of this model's size was made by reinit_matrix (a caller
    // reuses one over Newton's iterations): zero its entries and keep its
    // PETSc structure, instead of preallocating it anew every time.
    if (K_t && K_t->m() == n_dofs() && K_t->n() == n_dofs())
      *K_t = 0.;
    else if (K_t)
      reinit_matrix(*K_t);

    using CellIterator = typename DoFHandler<dim>::active_cell_iterator;
    const bool tangent = K_t != nullptr;
    auto copier = [this, f, K_t](const CellCopy &copy) {
      if (f && K_t)
        clamp_constraints.distribute_local_to_global(copy.matrix, copy.vector, copy.dofs, *K_t, *f);
      else if (f)
        clamp_constraints.distribute_local_to_global(copy.vector, copy.dofs, *f);
      else
        clamp_constraints.distribute_local_to_global(copy.matrix, copy.dofs, *K_t);
    };
    WorkStream::run(
      filter_iterators(dof_handler.active_cell_iterators(), IteratorFilters::LocallyOwnedCell()),
      [this, &u, tangent](const CellIterator &cell, StrainScratch<dim> &scratch, CellCopy &copy) {
        internal_force_on_cell(*this, u, tangent, cell, scratch, copy);
      },
      copier, StrainScratch<dim>(*cell_mapping, *fe, cell_quadrature), CellCopy(fe->n_dofs_per_cell()));
    if (f)
      f->compress(VectorOperation::add);
    if (K_t)
      K_t->compress(VectorOperation::add);
    if (!plates.empty())
      add_support_springs(u, f, K_t);
  }

  template class SolidModel<2>;
  template class SolidModel<3>;
} // namespace beamslider

