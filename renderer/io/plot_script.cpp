#include "renderer/io/plot_script.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "core/error.h"

namespace kappa {

void run_plot_script(const std::string& script_name, const std::vector<std::string>& args) {
  const std::string script = std::string(KAPPA_TOOLS_DIR) + "/" + script_name;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(script, ec)) throw InputError("--plot: " + script + " not found");
  std::vector<const char*> argv = {"/usr/bin/python3", script.c_str()};
  for (const std::string& a : args) argv.push_back(a.c_str());
  argv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("--plot: cannot start /usr/bin/python3: fork failed");
  if (pid == 0) {
    execv(argv[0], const_cast<char* const*>(argv.data()));
    _exit(127);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) throw std::runtime_error("--plot: lost track of /usr/bin/python3");
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  if (code == 127) throw InputError("--plot: /usr/bin/python3 is missing (run tools/setup.sh)");
  if (code == 3) throw InputError("--plot: python3-matplotlib is missing for /usr/bin/python3 (run tools/setup.sh)");
  if (code != 0) throw std::runtime_error("--plot: " + script + " failed (exit " + std::to_string(code) + ")");
}

JsonAndPlot::JsonAndPlot(const std::filesystem::path& json, const std::filesystem::path& plot, std::string script)
    : m_script(std::move(script)), m_json(optional_output(json)), m_plot(optional_output(plot, OutputKind::image)) {
  if (!m_plot) return;
  if (!m_json || m_json->direct()) m_plot_json = std::make_unique<MemoryFile>("kappa-plot-json");
  run_plot_script(m_script, {"--check"});
}

void JsonAndPlot::finish(const std::string& text) {
  if (m_json) write_temporary(*m_json, text);
  if (m_plot_json) {
    std::ofstream out(m_plot_json->path(), std::ios::binary | std::ios::trunc);
    out << text;
    if (!out.flush()) throw std::runtime_error("--plot: cannot write its JSON in memory");
  }
  if (m_plot)
    run_plot_script(m_script, {(m_plot_json ? m_plot_json->path() : m_json->temp_path()).string(), m_plot->temp_path().string()});
  const SignalsHeld held;
  if (m_json) m_json->commit();
  if (m_plot) m_plot->commit();
}

}  // namespace kappa
