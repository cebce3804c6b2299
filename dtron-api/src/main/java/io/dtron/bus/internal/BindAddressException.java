package io.dtron.bus.internal;

import java.io.IOException;
import java.net.InetAddress;

/** Not API. Nothing can listen on the bind address (not an address of this host): the message says so in one line. */
public final class BindAddressException extends IOException {
    private static final long serialVersionUID = 1L;

    BindAddressException(InetAddress address, IOException cause) {
        super("cannot listen on " + address.getHostAddress() + ", the bind address: " + cause.getMessage()
                + "; give an address of this host with the bind address option (dtron: --bind)", cause);
    }
}
