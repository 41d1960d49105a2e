// Child processes started with an argument vector (verification/
// child_process.h), in particular the early-started chart process: its
// arguments arrive intact whatever they hold, a child left without
// arguments gets an empty input, and a child that died before its input is
// written costs the parent neither a SIGPIPE nor a hang, only a reported
// failure.
#include "io/interruption.h"
#include "runtime/child_process.h"
#include "tests/read_text_file.h"

#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <pthread.h>

using namespace beamslider;
using beamslider::testing::read_file;
namespace fs = std::filesystem;

namespace
{
  fs::path scratch(const std::string &name)
  {
    const fs::path dir = fs::temp_directory_path() / ("beamslider_child_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    return dir / name;
  }
} // namespace

TEST(EarlyChild, ArgumentsArriveByteForByte)
{
  const fs::path out = scratch("arguments");
  // The test's own child is a fixed shell script; what it copies are the
  // arguments, which never pass through a shell.
  EarlyChild child({"/bin/sh", "-c", "cat > \"$0\"", out.string()});
  const std::vector<std::string> arguments = {"/tmp/a folder/x", "o';touch PWNED;'", "$(id)", "line\nbreak", "ü"};
  const ChildResult result = child.finish(arguments);
  EXPECT_TRUE(result.succeeded()) << result.error;
  std::string expected;
  for (const auto &a : arguments)
    expected += a + '\0';
  EXPECT_EQ(read_file(out), expected);
}

TEST(EarlyChild, WithoutFinishTheChildSeesAnEmptyInput)
{
  const fs::path out = scratch("empty");
  {
    EarlyChild child({"/bin/sh", "-c", "wc -c > \"$0\"", out.string()});
  } // destroyed: input closed unread, child waited for
  EXPECT_EQ(std::stoi(read_file(out)), 0);
}

TEST(EarlyChild, AChildThatDiedFirstIsAReportedFailureNotASignal)
{
  install_interruption_handlers(); // as beamslider's main(): SIGPIPE ignored
  EarlyChild child({"/bin/sh", "-c", "exit 3"});
  // More than a pipe buffer, so that the write must meet the closed end.
  const ChildResult result = child.finish({std::string(1 << 20, 'x')});
  EXPECT_TRUE(result.started);
  EXPECT_FALSE(result.succeeded());
  EXPECT_EQ(result.exit_code, 3);
  EXPECT_NE(result.error.find("status 3"), std::string::npos) << result.error;
}

TEST(EarlyChild, AMissingProgramIsNamed)
{
  EarlyChild child({"/nonexistent/python3", "script.py"});
  const ChildResult result = child.finish({"a"});
  EXPECT_FALSE(result.started);
  EXPECT_NE(result.error.find("/nonexistent/python3"), std::string::npos) << result.error;
}

// A measurement that starts `mpirun` or `beamslider` from a rank of an MPI
// launch (the map scaling study under `mpirun -n 2 beamslider verify`) must
// not hand that launch's variables on: the child would take them for its own
// launch and abort in MPI_Init. The child here checks its own environment
// (a fixed script, no user text).
TEST(RunChild, WithoutTheMPILaunchTheChildSeesNoneOfItsVariablesButTheRootOptIn)
{
  ASSERT_EQ(setenv("OMPI_COMM_WORLD_RANK", "1", 1), 0);
  ASSERT_EQ(setenv("PMIX_RANK", "1", 1), 0);
  ASSERT_EQ(setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1), 0);
  const std::vector<std::string> check = {
    "/bin/sh", "-c", "test -z \"$OMPI_COMM_WORLD_RANK\" && test -z \"$PMIX_RANK\" && test \"$OMPI_ALLOW_RUN_AS_ROOT\" = 1"};
  EXPECT_TRUE(run_child(check, ChildEnvironment::without_mpi_launch).succeeded());
  EXPECT_FALSE(run_child(check, ChildEnvironment::inherited).succeeded());
  unsetenv("OMPI_COMM_WORLD_RANK");
  unsetenv("PMIX_RANK");
}

// A chart runs in a process group of its own so that a terminal's Ctrl-C
// does not end it midway, but the child joins that group only once it runs:
// a Ctrl-C sent just before reached it (a CI run saw the chart "ended by
// signal 2"). It therefore starts with SIGINT blocked. The child here sends
// SIGINT to itself, as that early Ctrl-C does: it must end normally; a child
// of the shared group, which the run's Ctrl-C is meant to stop, must not.
TEST(RunChild, ASigintDoesNotEndAChildOfItsOwnGroupButEndsOneOfTheShared)
{
  // SIGINT as a terminal's foreground job has it, whatever this test
  // inherited (a background job of a non-interactive shell ignores it, and
  // an ignored signal stays ignored in the child).
  std::signal(SIGINT, SIG_DFL);
  sigset_t interrupt;
  sigemptyset(&interrupt);
  sigaddset(&interrupt, SIGINT);
  pthread_sigmask(SIG_UNBLOCK, &interrupt, nullptr);
  const std::vector<std::string> interrupt_self = {"/bin/sh", "-c", "kill -INT $$; exit 0"};
  const ChildResult own = run_child(interrupt_self, ChildEnvironment::inherited, ChildGroup::own);
  EXPECT_TRUE(own.succeeded()) << own.error;
  const ChildResult shared = run_child(interrupt_self, ChildEnvironment::inherited, ChildGroup::shared);
  EXPECT_EQ(shared.signal, SIGINT) << shared.error;
}
