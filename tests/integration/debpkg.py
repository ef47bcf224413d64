# SPDX-License-Identifier: Apache-2.0
"""debpkg — a Python master whose import fails names the Debian package to install.

    try:
        from pymodbus.client import ModbusSerialClient
    except ImportError as e:
        debpkg.missing(e)
"""
import sys

# Module → Debian package. pymodbus's serial client imports serial and serial_asyncio,
# which python3-pymodbus only recommends: tools/install-deps names all three.
PACKAGES = {
    "pymodbus": "python3-pymodbus",
    "serial": "python3-serial",
    "serial_asyncio": "python3-serial-asyncio",
}


def missing(err):
    """Report an ImportError with the package that provides the module, and fail."""
    name = (getattr(err, "name", None) or str(err)).split(".")[0]
    pkg = PACKAGES.get(name, "the Debian package that provides it")
    print(f"{sys.argv[0]}: cannot import Python module {name!r} ({err}); install Debian's {pkg} "
          f"(tools/install-deps does) and run the test with /usr/bin/python3, not {sys.executable}",
          flush=True)
    print("0 passed, 1 failed")
    sys.exit(1)
