// One failure for all ranks, see collective_failure.h.
#include "output/collective_failure.h"

#include "io/output_file.h"
#include "fem/petsc_session.h"
#include "scene/scene.h"

#include <deal.II/base/mpi.h>

#include <exception>
#include <stdexcept>
#include <string>

namespace beamslider
{
  namespace
  {
    // The kinds of error the command line tells apart (exit 2 or 1, and the
    // folder-in-use message), as the first character of what is broadcast.
    enum Kind : char
    {
      input = 'i',
      folder_in_use = 'f',
      output = 'o',
      invalid_argument = 'a',
      other = 'x'
    };

    [[noreturn]] void throw_as(const char kind, const std::string &message)
    {
      switch (kind)
        {
          case input:
            throw InputError(message);
          case folder_in_use:
            throw FolderInUseError(message);
          case output:
            throw OutputError(message);
          case invalid_argument:
            throw std::invalid_argument(message);
          default:
            throw std::runtime_error(message);
        }
    }

    // The kind and message of an error.
    std::string describe(const std::exception_ptr &error)
    {
      try
        {
          std::rethrow_exception(error);
        }
      catch (const InputError &e)
        {
          return std::string(1, input) + e.what();
        }
      catch (const FolderInUseError &e)
        {
          return std::string(1, folder_in_use) + e.what();
        }
      catch (const OutputError &e)
        {
          return std::string(1, output) + e.what();
        }
      catch (const std::invalid_argument &e)
        {
          return std::string(1, invalid_argument) + e.what();
        }
      catch (const std::exception &e)
        {
          return std::string(1, other) + e.what();
        }
      catch (...)
        {
          return std::string(1, other) + "unknown error";
        }
    }
  } // namespace

  void fail_together(const MPI_Comm comm, const std::function<void()> &work)
  {
    if (!mpi_started() || dealii::Utilities::MPI::n_mpi_processes(comm) == 1)
      {
        work();
        return;
      }
    std::exception_ptr caught;
    try
      {
        work();
      }
    catch (...)
      {
        caught = std::current_exception();
      }
    const std::string failure = caught ? describe(caught) : std::string(); // "" if the work succeeded here
    const unsigned int rank = dealii::Utilities::MPI::this_mpi_process(comm),
                       none = dealii::Utilities::MPI::n_mpi_processes(comm);
    const unsigned int first = dealii::Utilities::MPI::min(failure.empty() ? none : rank, comm);
    if (first == none)
      return;
    const std::string first_failure = dealii::Utilities::MPI::broadcast(comm, failure, first);
    if (rank == first)
      std::rethrow_exception(caught); // its own error, as it was
    throw_as(first_failure[0], first_failure.substr(1));
  }
} // namespace beamslider
