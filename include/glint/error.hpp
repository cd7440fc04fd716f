#pragma once
// glint's exception types. Every error the library reports is a glint::Error, so a program can
// catch them all in one place; the subclasses say which kind of input was wrong, so that it
// can react (an exit status, a message form) without reading the message text.

#include <stdexcept>
#include <string>

namespace glint {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// RenderSettings (or a driver's option) outside what the renderer accepts.
class SettingsError : public Error {
 public:
  using Error::Error;
};

/// An image could not be written; nothing (not even a truncated file) was left behind.
class ImageWriteError : public Error {
 public:
  using Error::Error;
};

/// An image file could not be read or is not in the expected format.
class ImageReadError : public Error {
 public:
  using Error::Error;
};

}  // namespace glint
