// The files of member runs, see member_files.h.
#include "verification/report/member_files.h"

#include "io/csv_writer.h"
#include "io/input_file.h"
#include "io/output_file.h"
#include "io/console.h"
#include "numerics/state_bytes.h"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

namespace beamslider
{
  namespace
  {
    // A check round's file: member_runs.csv → member_runs.check-<round>.csv.
    constexpr const char *check_infix = ".check-";

    // The records of a CSV text: lines, except that a line break inside a
    // quoted cell belongs to the cell. A last record without its '\n' (a
    // write cut short) is returned too; its checks reject it.
    std::vector<std::string> records(const std::string &text)
    {
      std::vector<std::string> out;
      std::string current;
      bool in_quotes = false;
      for (const char c : text)
        {
          if (c == '"')
            in_quotes = !in_quotes; // "" inside quotes toggles twice
          if (c == '\n' && !in_quotes)
            {
              out.push_back(std::move(current));
              current.clear();
            }
          else
            current += c;
        }
      if (!current.empty())
        out.push_back(std::move(current));
      return out;
    }

    // One member_runs.csv, which rank 0 appends each finished member to.
    struct MemberFile
    {
      MemberFile(const std::string &file_stem, const std::string &prefix,
                 const std::function<void(const std::string &)> &progress)
        : stem(file_stem), path(file_stem + ".csv"), progress_prefix(prefix), on_progress(progress)
      {}

      // The rows of an earlier start with this key, each offered to `take`
      // as its cells (a file of another key moved aside), the file anew with
      // the rows taken only, then open for appending.
      void open(const std::string &key, const std::vector<std::string> &columns,
                const std::function<bool(const std::vector<std::string> &record)> &take)
      {
        std::string kept = "# " + key + "\n" + CsvWriter::line(columns) + "\n";
        const std::vector<std::string> previous = records(read_text_file_if_present(path));
        if (!previous.empty() && previous.front() != "# " + key)
          {
            std::filesystem::rename(path, stem + ".other.csv");
            if (on_progress)
              on_progress(progress_prefix + path + " holds the members of other settings: not reused, moved to " +
                          stem + ".other.csv; every member is run afresh");
          }
        else
          for (std::size_t k = 2; k < previous.size(); ++k)
            if (take(CsvWriter::cells(previous[k])))
              kept += previous[k] + "\n";
        // The file anew with the complete rows only (atomically: a kill now
        // leaves the old file or the new one); new rows are appended.
        write_file_atomically(path, kept);
        CsvOptions append;
        append.append = true;
        rows.emplace(path, columns, append);
      }

      const std::string stem, path, progress_prefix;
      const std::function<void(const std::string &)> on_progress;
      std::optional<CsvWriter> rows;
    };

    MemberRecordStore member_file_store(const std::string &stem, const std::string &progress_prefix,
                                        const std::function<void(const std::string &line)> &on_progress)
    {
      const auto file = std::make_shared<MemberFile>(stem, progress_prefix, on_progress);
      MemberRecordStore store;
      store.name = file->path;
      store.open = [file](const std::string &key, const std::vector<std::string> &columns,
                          const std::function<bool(const std::vector<std::string> &record)> &take) {
        file->open(key, columns, take);
      };
      store.append = [file](const std::vector<std::string> &record) { file->rows->row(record); };
      store.close  = [file] { file->rows->close(); };
      return store;
    }
  } // namespace

  std::function<MemberRecordStore(unsigned int round)>
  member_files(const std::string &dir, const std::string &file, const std::string &progress_prefix,
               const std::function<void(const std::string &line)> &on_progress)
  {
    if (dir.empty())
      return {};
    const std::string stem = dir + "/" + file.substr(0, file.rfind(".csv"));
    return [stem, progress_prefix, on_progress](const unsigned int round) {
      // member_runs.csv → member_runs.check-1.csv, …
      return member_file_store(round == 0 ? stem : stem + check_infix + std::to_string(round), progress_prefix,
                               on_progress);
    };
  }

  std::shared_ptr<const unsigned int> count_check_rounds(MemberRunsSettings &settings)
  {
    auto highest = std::make_shared<unsigned int>(0);
    if (settings.records)
      settings.records = [inner = settings.records, highest](const unsigned int round) {
        *highest = std::max(*highest, round);
        return inner(round);
      };
    return highest;
  }

  void remove_unreached_check_files(const std::string &dir, const std::string &file, const unsigned int rounds_used)
  {
    if (dir.empty())
      return;
    const std::string head = file.substr(0, file.rfind(".csv")) + check_infix, tail = ".csv";
    std::vector<std::filesystem::path> unreached;
    std::error_code ec;
    for (std::filesystem::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
      {
        const std::string name = it->path().filename().string();
        if (name.size() <= head.size() + tail.size() || name.compare(0, head.size(), head) != 0 ||
            name.compare(name.size() - tail.size(), tail.size(), tail) != 0)
          continue;
        const std::string round = name.substr(head.size(), name.size() - head.size() - tail.size());
        if (round.find_first_not_of("0123456789") == std::string::npos && round.size() < 6 &&
            std::stoul(round) > rounds_used)
          unreached.push_back(it->path());
      }
    for (const std::filesystem::path &path : unreached)
      std::filesystem::remove(path, ec);
  }

  MemberRunsSettings member_files_settings(const std::string &dir, const std::string &study, const MpiSession *mpi,
                                           const std::string &progress_prefix, const std::string &file)
  {
    MemberRunsSettings settings;
    settings.study           = study;
    settings.mpi             = mpi;
    settings.progress_prefix = progress_prefix;
    settings.on_progress     = [](const std::string &line) { console() << line << std::endl; };
    settings.records         = member_files(dir, file, progress_prefix, settings.on_progress);
    return settings;
  }
  namespace
  {
    std::atomic<std::size_t> shared_reused{0}, shared_kept{0};
    std::mutex shared_folder_mutex;
    std::string shared_folder;

    void note_shared_folder(const std::string &path)
    {
      const std::lock_guard<std::mutex> lock(shared_folder_mutex);
      shared_folder = std::filesystem::path(path).parent_path().string();
    }

    std::string shared_member_path(const std::string &dir, const MemberGroup &group, const std::string &key)
    {
      char hash[17];
      std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(fnv1a(key)));
      return (std::filesystem::path(dir) / group.scene.name / "fe_members" / (std::string(hash) + ".csv")).string();
    }

    std::string shared_member_title(const std::string &key) { return "# beamslider member, key: " + key; }
  } // namespace

  void share_fe_members(MemberRunsSettings &settings, const std::string &dir)
  {
    settings.cached = [dir](const MemberGroup &group,
                            const std::string &key) -> std::optional<std::vector<std::string>> {
      if (group.model.family != "fe")
        return std::nullopt;
      std::vector<std::string> lines;
      try
        {
          lines = records(read_text_file_if_present(shared_member_path(dir, group, key), InputLimits::table));
        }
      catch (const FileReadError &)
        {
          return std::nullopt; // a FIFO, a folder, no permission: run the member
        }
      if (lines.size() != 3 || lines[0] != shared_member_title(key) ||
          lines[1] != CsvWriter::line(member_record_columns()))
        return std::nullopt;
      note_shared_folder(shared_member_path(dir, group, key));
      ++shared_reused;
      return CsvWriter::cells(lines[2]);
    };
    settings.remember = [dir](const MemberGroup &group, const std::string &key,
                              const std::vector<std::string> &record) {
      if (group.model.family != "fe")
        return;
      try
        {
          const std::string path = shared_member_path(dir, group, key);
          std::filesystem::create_directories(std::filesystem::path(path).parent_path());
          write_file_atomically(path, shared_member_title(key) + "\n" + CsvWriter::line(member_record_columns()) +
                                        "\n" + CsvWriter::line(record) + "\n");
          note_shared_folder(path);
          ++shared_kept;
        }
      catch (const std::exception &)
        {
          // Not kept: a later report runs this member again.
        }
    };
  }

  SharedMemberCounts shared_member_counts()
  {
    const std::lock_guard<std::mutex> lock(shared_folder_mutex);
    return {shared_reused.load(), shared_kept.load(), shared_folder};
  }
} // namespace beamslider
