package io.dtron.bus.internal;

import java.io.IOException;
import java.util.List;

/**
 * Not API. No bus port of the settings was free: the message names the ports in use and the options that choose
 * others.
 */
public final class PortsInUseException extends IOException {
    private static final long serialVersionUID = 1L;

    PortsInUseException(JGroupsSettings settings, List<Integer> inUse) {
        super("no free port for the bus on " + settings.bindAddress().getHostAddress() + " in "
                + settings.port() + ".." + (settings.port() + settings.portRange()) + " (port "
                + settings.port() + ", port range " + settings.portRange() + "): a member needs one, and ports "
                + ranges(inUse) + " are in use; choose free ones with the port and port range options (dtron: --port,"
                + " --port-range)");
    }

    /** The ports as ascending runs: {@code 7800-7802, 7815}. */
    static String ranges(List<Integer> ports) {
        List<Integer> sorted = ports.stream().distinct().sorted().toList();
        StringBuilder text = new StringBuilder();
        for (int i = 0; i < sorted.size(); i++) {
            int first = sorted.get(i);
            while (i + 1 < sorted.size() && sorted.get(i + 1) == sorted.get(i) + 1) {
                i++;
            }
            text.append(text.length() == 0 ? "" : ", ").append(first)
                    .append(sorted.get(i) == first ? "" : "-" + sorted.get(i));
        }
        return text.toString();
    }
}
