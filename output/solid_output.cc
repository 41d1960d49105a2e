#include "output/solid_output.h"

#include "io/output_file.h"
#include "output/collective_failure.h"

#include <deal.II/base/mpi.h>
#include <deal.II/numerics/data_component_interpretation.h>
#include <deal.II/numerics/data_out.h>

#include <cstdio>
#include <iomanip>
#include <sstream>

namespace beamslider
{
  using namespace dealii;

  namespace
  {
    std::string piece_name(const std::string &basename, const unsigned int rank)
    {
      std::ostringstream s;
      s << basename << "_" << std::setw(4) << std::setfill('0') << rank << ".vtu";
      return s.str();
    }

    // Writes into `path` with `write`; OutputError if it cannot.
    template <typename Writer>
    void write_checked(const std::string &path, const Writer &write)
    {
      // A checked OutputFile: whole (a temporary renamed into place), never
      // written through a link.
      OutputFile out(path);
      try
        {
          write(out.stream());
        }
      catch (const std::exception &)
        {
          out.check(); // a failed write (deal.II's ExcIO): the file and the system's reason
          throw;
        }
      out.close();
    }
  } // namespace

  template <int dim>
  std::string write_solid_fields(const SolidModel<dim> &model, const std::vector<SolidField> &fields,
                                 const std::string &folder, const std::string &basename)
  {
    const MPI_Comm comm = model.communicator();
    const unsigned int rank = Utilities::MPI::this_mpi_process(comm), n_ranks = Utilities::MPI::n_mpi_processes(comm);

    // Scaled ghosted copies (a ghosted vector cannot be scaled in place).
    std::vector<PETScWrappers::MPI::Vector> scaled(fields.size());
    DataOut<dim> data_out;
    data_out.attach_dof_handler(model.get_dof_handler());
    const std::vector<DataComponentInterpretation::DataComponentInterpretation> vector_field(
      dim, DataComponentInterpretation::component_is_part_of_vector);
    for (unsigned int i = 0; i < fields.size(); ++i)
      {
        PETScWrappers::MPI::Vector owned;
        model.reinit_vector(owned);
        owned = *fields[i].displacement;
        owned *= fields[i].scale;
        model.reinit_ghosted_vector(scaled[i]);
        scaled[i] = owned;
        data_out.add_data_vector(scaled[i], std::vector<std::string>(dim, fields[i].name),
                                 DataOut<dim>::type_dof_data, vector_field);
      }
    // Which rank owns each cell, for a look at the partition in ParaView.
    Vector<float> owner(model.get_dof_handler().get_triangulation().n_active_cells());
    owner = static_cast<float>(rank);
    data_out.add_data_vector(owner, "rank");
    // Simplex cells are written as they are (deal.II subdivides only
    // hypercubes); a hex cell of degree p as p^dim sub-cells.
    data_out.build_patches(model.mapping(), model.simplex() ? 1 : model.get_dof_handler().get_fe().degree);

    // Each rank its piece, then rank 0 the record that lists them. A piece
    // that fails on one rank (a full disk) fails the write on every rank:
    // all remove their pieces, so no record or piece of a broken set stays.
    const std::string piece = folder + "/" + piece_name(basename, rank), record = folder + "/" + basename + ".pvtu";
    try
      {
        fail_together(comm, [&] { write_checked(piece, [&](std::ostream &out) { data_out.write_vtu(out); }); });
        fail_together(comm, [&] {
          if (rank != 0)
            return;
          std::vector<std::string> pieces;
          for (unsigned int r = 0; r < n_ranks; ++r)
            pieces.push_back(piece_name(basename, r));
          write_checked(record, [&](std::ostream &out) { data_out.write_pvtu_record(out, pieces); });
        });
      }
    catch (...)
      {
        std::remove(piece.c_str());
        throw;
      }
    return record;
  }

  template std::string write_solid_fields(const SolidModel<2> &, const std::vector<SolidField> &, const std::string &,
                                          const std::string &);
  template std::string write_solid_fields(const SolidModel<3> &, const std::vector<SolidField> &, const std::string &,
                                          const std::string &);
} // namespace beamslider
