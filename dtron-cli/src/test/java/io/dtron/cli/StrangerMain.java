package io.dtron.cli;

import io.dtron.api.Dtron;
import io.dtron.api.DtronOptions;
import io.dtron.api.IDtronChannel;
import java.nio.file.Path;
import java.util.Map;
import java.util.concurrent.TimeUnit;

/**
 * A process on a bus, maybe without the bus's secret: joins bus {@code args[0]} on the ports {@code args[1]} to
 * {@code args[1] + args[2]} with the key file {@code args[3]} ({@code --insecure}: none; {@code --default}: the
 * default key file), prints {@code members [...]} at joining and at every change of its members, and then, every
 * 50 ms for five minutes at most (until it is killed), forges what would fail a run of the ticker if anyone took it:
 * a {@code tick} with a sequence number no ticker sends, and a {@code reset} input.
 */
public final class StrangerMain {
    private StrangerMain() {
    }

    public static void main(String[] args) throws Exception {
        DtronOptions.Builder options = DtronOptions.builder().clusterName(args[0]).memberName("stranger")
                .port(Integer.parseInt(args[1])).portRange(Integer.parseInt(args[2]));
        if (args[3].equals("--insecure")) {
            options.insecure(true);
        } else if (!args[3].equals("--default")) {
            options.keyFile(Path.of(args[3]));
        }
        IDtronChannel tick = IDtronChannel.of("tick", "seq");
        IDtronChannel reset = IDtronChannel.of("reset");
        try (Dtron stranger = Dtron.connect(options.build())) {
            stranger.addMembershipListener((members, joined, left) -> print("members " + members));
            print("members " + stranger.getMembers());
            long end = System.nanoTime() + TimeUnit.MINUTES.toNanos(5);
            while (System.nanoTime() < end) {
                stranger.send(tick.constructValued(Map.of("seq", 777)));
                stranger.send(reset.constructValued(Map.of()));
                Thread.sleep(50);
            }
        }
    }

    private static synchronized void print(String line) {
        System.out.println(line);
        System.out.flush();
    }
}
