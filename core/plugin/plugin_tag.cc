#include "plugin/plugin_tag.h"

#include <elf.h>

#include <cctype>
#include <cstring>
#include <fstream>
#include <vector>

namespace hull::plugin {
namespace {

constexpr char kSection[] = ".hullinspect_plugin";
constexpr char kPrefix[] = "HULLINSPECT_PLUGIN ";
constexpr std::uint64_t kMaxTag = 4096;

bool Fail(std::string* why, const std::string& message) {
  if (why) *why = message;
  return false;
}

// Reads `size` bytes at `offset`; false when the file is shorter.
bool ReadAt(std::ifstream& in, std::uint64_t offset, void* out, std::uint64_t size) {
  in.clear();
  in.seekg(static_cast<std::streamoff>(offset));
  if (!in) return false;
  in.read(static_cast<char*>(out), static_cast<std::streamsize>(size));
  return static_cast<std::uint64_t>(in.gcount()) == size;
}

}  // namespace

bool ParsePluginTag(const std::string& text, PluginTag* tag, std::string* why) {
  if (text.compare(0, std::strlen(kPrefix), kPrefix) != 0) {
    return Fail(why, "its plugin tag does not start with \"HULLINSPECT_PLUGIN \"");
  }
  std::size_t pos = std::strlen(kPrefix);
  if (text.compare(pos, 4, "abi=") != 0) return Fail(why, "its plugin tag has no abi=");
  pos += 4;
  const std::size_t digits_end = text.find_first_not_of("0123456789", pos);
  if (digits_end == pos || digits_end == std::string::npos || digits_end - pos > 6) {
    return Fail(why, "its plugin tag has no ABI version number");
  }
  const int abi = std::stoi(text.substr(pos, digits_end - pos));
  pos = digits_end;
  if (text.compare(pos, 6, " name=") != 0) return Fail(why, "its plugin tag has no name=");
  const std::string name = text.substr(pos + 6);
  if (name.empty() || name.size() > 64) return Fail(why, "its plugin name is empty or longer than 64 characters");
  for (char c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') {
      return Fail(why, "its plugin name '" + name + "' has characters other than letters, digits, '-' and '_'");
    }
  }
  tag->abi = abi;
  tag->name = name;
  return true;
}

bool ReadPluginTag(const std::string& path, PluginTag* tag, std::string* why) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Fail(why, "cannot open the file");
  Elf64_Ehdr eh{};
  if (!ReadAt(in, 0, &eh, sizeof eh) || std::memcmp(eh.e_ident, ELFMAG, SELFMAG) != 0) {
    return Fail(why, "not an ELF shared object");
  }
  if (eh.e_ident[EI_CLASS] != ELFCLASS64 || eh.e_ident[EI_DATA] != ELFDATA2LSB) {
    return Fail(why, "not a 64-bit little-endian ELF file");
  }
  if (eh.e_type != ET_DYN) return Fail(why, "an ELF file but not a shared object");
  if (eh.e_shentsize != sizeof(Elf64_Shdr) || eh.e_shnum == 0 || eh.e_shstrndx >= eh.e_shnum) {
    return Fail(why, "its ELF section table is missing or malformed");
  }
  std::vector<Elf64_Shdr> sections(eh.e_shnum);
  if (!ReadAt(in, eh.e_shoff, sections.data(), sizeof(Elf64_Shdr) * sections.size())) {
    return Fail(why, "its ELF section table lies beyond the end of the file");
  }
  const Elf64_Shdr& names = sections[eh.e_shstrndx];
  if (names.sh_size > (1u << 24)) return Fail(why, "its ELF section names are implausibly large");
  std::vector<char> strtab(names.sh_size + 1, '\0');
  if (!ReadAt(in, names.sh_offset, strtab.data(), names.sh_size)) {
    return Fail(why, "its ELF section names lie beyond the end of the file");
  }
  for (const Elf64_Shdr& s : sections) {
    if (s.sh_name >= names.sh_size || std::strcmp(strtab.data() + s.sh_name, kSection) != 0) continue;
    if (s.sh_type == SHT_NOBITS || s.sh_size == 0 || s.sh_size > kMaxTag) {
      return Fail(why, "its .hullinspect_plugin section is empty or too large");
    }
    std::string text(s.sh_size, '\0');
    if (!ReadAt(in, s.sh_offset, text.data(), s.sh_size)) {
      return Fail(why, "its .hullinspect_plugin section lies beyond the end of the file");
    }
    text.resize(text.find('\0') == std::string::npos ? text.size() : text.find('\0'));
    return ParsePluginTag(text, tag, why);
  }
  return Fail(why, "not a HullInspect plugin (no .hullinspect_plugin section: HULLINSPECT_PLUGIN missing)");
}

}  // namespace hull::plugin
