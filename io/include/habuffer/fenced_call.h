/// @file
/// A third-party reader that trusts its input, run where it cannot take the
/// process down. OpenVDB's reader, given a file with a few bytes changed,
/// corrupts its heap and aborts (`malloc(): invalid size`) or allocates what
/// a corrupt count asks for; no exception reaches the caller. `fenced_call`
/// runs such work in a forked child process:
///
/// - the child runs `work`, which returns its result as bytes; they come back
///   through a pipe, so the work's own allocations, and any heap it corrupts,
///   die with the child;
/// - an exception in the child comes back as its message, thrown as
///   DataError;
/// - a child that dies by a signal (SIGABRT, SIGSEGV, SIGBUS, SIGKILL from
///   the kernel's out-of-memory killer) is one DataError naming `what` and
///   the signal;
/// - the child's new memory and its CPU time are limited (FenceLimits: the
///   caller sizes them by its input), so a corrupt count fails there with
///   std::bad_alloc, and a reader that loops is stopped, rather than
///   swapping the machine or hanging (RLIMIT_DATA above what the child
///   starts with: the sanitizers' allocators are held to it as well).
///
/// Cost: one fork (the parent's pages shared copy-on-write) and one copy of
/// the result, measured in docs/performance.md ("Fenced readers").
///
/// The child uses no thread the parent made: work that starts threads must
/// start its own (oneTBB's arena in a fresh child does). Signals that end the
/// parent (SIGINT, SIGTERM, SIGHUP) end the child at once, without the
/// parent's handlers (habuffer/atomic_file.h: the parent removes its
/// temporaries).
#pragma once

#include <cstdint>
#include <functional>
#include <string>

namespace habuffer {

/// What the child may use beyond what it shares with the parent.
struct FenceLimits {
  std::uint64_t memory_bytes = 0;  ///< new address space; 0: this machine's memory
  std::uint32_t cpu_seconds = 60;  ///< CPU time; SIGXCPU ends the child past it
};

/// Runs `work` in a child process and returns what it returned (see the
/// file comment). `what` names the input for messages ("g.vdb: OpenVDB's
/// reader"). Throws DataError: the child's exception message as it is, or
/// "WHAT crashed on it (SIGABRT, ...): the file is corrupt or not what it
/// claims to be", "WHAT used more than N s of CPU time ..." or "WHAT needs
/// more than N MiB ..."; std::runtime_error when no process can be made.
std::string fenced_call(const std::string& what, const std::function<std::string()>& work, FenceLimits limits = {});

}  // namespace habuffer
