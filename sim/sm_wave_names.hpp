// The signals a wave file declares, named as GTKWave names them (and as .gtkw save files
// list them): the scope path joined with '.', the signal name, its bit range without a
// space, e.g. "TOP.sm_top.u_dp.disp_out[15:0]". VCD is read as text (the header up to
// $enddefinitions); FST with the reader of GTKWave's fstapi, which Verilator's FST writer
// (verilated_fst_c.cpp) compiles in, so FST files are readable where an FST model is linked.
#pragma once

#include <cctype>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "lower_case.hpp"

#if VM_TRACE_FST
#include <gtkwave/fstapi.h>
#endif

namespace sm {

// The wave format a path names: its extension without the dot, lower-cased ("vcd", "fst").
inline std::string wave_extension(const std::string& path) {
  const std::string ext = lower_extension(path);
  return ext.empty() ? ext : ext.substr(1);
}

namespace detail {
inline std::string join_scope(const std::vector<std::string>& scope, const std::string& name) {
  std::string s;
  for (const auto& p : scope) s += p + ".";
  return s + name;
}
}  // namespace detail

inline std::vector<std::string> vcd_signal_names(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(fmt::format("{}: cannot open", path));
  std::vector<std::string> names, scope;
  std::string tok;
  bool ended = false;
  while (in >> tok) {
    if (tok == "$scope") {
      std::string kind, name;
      in >> kind >> name;
      scope.push_back(name);
    } else if (tok == "$upscope") {
      if (scope.empty()) throw std::runtime_error(fmt::format("{}: $upscope without $scope", path));
      scope.pop_back();
    } else if (tok == "$var") {
      std::string type, width, id, name, t;
      in >> type >> width >> id >> name;
      while (in >> t && t != "$end") name += t;  // the bit range: "[15:0]"
      names.push_back(detail::join_scope(scope, name));
    } else if (tok == "$enddefinitions") {
      ended = true;
      break;
    }
  }
  if (!ended) throw std::runtime_error(fmt::format("{}: not a VCD file (no $enddefinitions)", path));
  return names;
}

#if VM_TRACE_FST
inline std::vector<std::string> fst_signal_names(const std::string& path) {
  void* ctx = fstReaderOpen(path.c_str());
  if (!ctx) throw std::runtime_error(fmt::format("{}: not an FST file", path));
  std::vector<std::string> names, scope;
  while (const fstHier* h = fstReaderIterateHier(ctx)) {
    if (h->htyp == FST_HT_SCOPE) {
      scope.emplace_back(h->u.scope.name, h->u.scope.name_length);
    } else if (h->htyp == FST_HT_UPSCOPE) {
      if (!scope.empty()) scope.pop_back();
    } else if (h->htyp == FST_HT_VAR) {
      std::string n(h->u.var.name, h->u.var.name_length);
      const size_t sp = n.find(" [");  // Verilator writes "name [15:0]"
      if (sp != std::string::npos) n.erase(sp, 1);
      // Verilator 5.04x's FST writer puts the elements of an unpacked array in a scope of
      // the array's name ("tag_q" holding "tag_q[0]"); 5.006 and the VCD writers do not.
      // Named without that scope, an element is named alike in every file.
      if (!scope.empty() && n.size() > scope.back().size() && n.compare(0, scope.back().size(), scope.back()) == 0 &&
          n[scope.back().size()] == '[') {
        std::vector<std::string> outer(scope.begin(), scope.end() - 1);
        names.push_back(detail::join_scope(outer, n));
        continue;
      }
      names.push_back(detail::join_scope(scope, n));
    }
  }
  fstReaderClose(ctx);
  return names;
}
#endif

// The signal names of a .vcd or .fst file.
inline std::vector<std::string> wave_signal_names(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw std::runtime_error(fmt::format("{}: is a directory", path));
  const std::string ext = wave_extension(path);
  if (ext == "vcd") return vcd_signal_names(path);
#if VM_TRACE_FST
  if (ext == "fst") return fst_signal_names(path);
#endif
  throw std::runtime_error(fmt::format("{}: cannot read .{} wave files here (this program reads {})", path, ext,
#if VM_TRACE_FST
                                       ".vcd and .fst"
#else
                                       ".vcd"
#endif
                                       ));
}

}  // namespace sm
