#pragma once
// Work the real-time loop hands off: parameter storage (file open, write,
// fsync, rename; flash erase) takes milliseconds and must not run in the
// CAN service of the 1 ms cycle. The node fills a job (the image to write,
// or where to decode a read), posts it and returns at once; a worker on a
// non-real-time thread (or, on the HIL rigs, the rig between two ticks)
// calls run(); the node sees the job done in a later service() and answers
// the request then. Interface only: the worker lives in drivers/.
namespace tnv::hal {

class StorageJob {
 public:
  // Runs on the worker's thread, never the real-time one. Touches only the
  // job's own buffers and the storage it was given.
  virtual void run() noexcept = 0;

 protected:
  ~StorageJob() = default;
};

class StorageWorker {
 public:
  virtual ~StorageWorker() = default;
  // Hands `job` over without blocking, allocating or a system call; false
  // (nothing posted) while the previous job is not yet collected by done().
  virtual bool post(StorageJob& job) noexcept = 0;
  // True once the posted job's run() has returned: its results are visible
  // to the caller and the worker takes the next post(). False when busy or
  // when nothing was posted. Never blocks.
  virtual bool done() noexcept = 0;
};

}  // namespace tnv::hal
