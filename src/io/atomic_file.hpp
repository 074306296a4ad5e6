// Output files written atomically (docs/cli.md): rows go to a temporary file
// beside the target, which is renamed into place only by commit(), so a run
// that fails or diverges leaves no file behind; the checks that an output
// path can be written before any work starts; and the lock that keeps two
// runs out of one output directory.
#pragma once

#include <cstdio>
#include <string>

namespace contact2d {

// What an output path names, and how it is written (docs/cli.md):
//  - a regular file, or none yet: replaced atomically (a temporary beside it,
//    renamed onto it at commit);
//  - a symbolic link to a regular file: that file, the same way (the link
//    stays); a link to a file that does not exist is refused
//    (check_output_file);
//  - a FIFO, a character or block device, a socket, or a link into /proc
//    (/dev/stdout, /dev/fd/N): written through at commit, never replaced or
//    removed (stream); the output waits in the temporary directory until then.
struct OutputTarget {
  std::string path;     // the file that is replaced (symlinks followed), or `path` itself
  bool stream = false;  // written through
};
OutputTarget output_target(const std::string& path);

class AtomicFile {
 public:
  // Opens a temporary file "PATH.tmp.PID.XXXXXX" in the target's directory
  // ("$TMPDIR/contact2d.stream.PID.XXXXXX" for a target written through);
  // throws InputError (from io/scene_file.hpp) when the directory does not
  // exist or is not writable. First it removes the temporaries of the same
  // PATH that a killed run left (SIGKILL cannot be caught): those whose PID
  // is no longer running, or is running a process started after the file
  // was last written (the PID was reused).
  explicit AtomicFile(std::string path);
  ~AtomicFile();  // removes the temporary file unless committed
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::FILE* get() const { return file_; }
  const std::string& path() const { return path_; }  // the output path, as given
  bool streams() const { return target_.stream; }    // written through at commit
  // The temporary file's path, for a writer that opens it by name (gnuplot);
  // flush get() first if it was written through too.
  const std::string& temp_path() const { return temp_path_; }
  void commit();  // flush, close, rename; throws InputError on failure

 private:
  std::string path_;
  OutputTarget target_;
  std::string temp_path_;
  std::FILE* file_ = nullptr;
  int slot_ = -1;  // io/interrupt.hpp: removed if a signal ends the program first
};

// Checks, before any work, that `path` can become an output file: not empty,
// not a directory, inside a directory that exists and is writable. Throws
// InputError naming `option` ("--plot out/no/p.png: directory out/no does
// not exist"), so that a run with one bad output path writes nothing at all.
void check_output_file(const std::string& option, const std::string& path);

// The same for an output directory, which is created when missing: it, or
// else its nearest existing ancestor, must be a writable directory.
void check_output_directory(const std::string& option, const std::string& path);

// An exclusive lock on an output directory, held while alive: flock() on
// DIR/.contact2d.lock, which holds the owner's PID and is removed when the
// lock is released (and by the interrupt handler, io/interrupt.hpp). A second
// process locking the same directory meanwhile gets an InputError naming
// `option`, the directory and the owner's PID. The kernel releases a flock()
// when its owner dies, SIGKILL included, so a lock file a killed run left
// behind does not block the next one. The directory must exist.
class DirectoryLock {
 public:
  DirectoryLock(const std::string& option, const std::string& dir);
  ~DirectoryLock();
  DirectoryLock(const DirectoryLock&) = delete;
  DirectoryLock& operator=(const DirectoryLock&) = delete;

 private:
  std::string path_;
  int fd_ = -1;
  int slot_ = -1;
};

}  // namespace contact2d
