package io.dtron.bus.internal;

import java.nio.charset.StandardCharsets;
import java.util.Arrays;

/**
 * What the message codes of a NATS bus cost one message, in this JVM: making the code of a tick as its sender does,
 * and checking it as a receiver does (code, replay window, time), each timed alone. Prints count, p50, p99 and max
 * in nanoseconds after a warm-up. Argument (optional): the number of messages (default 200,000).
 */
public final class MessageCodesBench {
    private MessageCodesBench() {
    }

    public static void main(String[] args) {
        int n = args.length > 0 ? Integer.parseInt(args[0]) : 200_000;
        MessageCodes codes = MessageCodes.forSecret("0123456789abcdef0123456789abcdef0123456789abcdef0123456789abcdef"
                .getBytes(StandardCharsets.UTF_8));
        // a tick as the ticker adapter sends it: a Sync of about 60 bytes
        byte[] data = new byte[60];
        Arrays.fill(data, (byte) 7);
        String subject = "dtron.bench-0a1b2c3d.c.tick";
        String sender = "dtron-123456-0a1b2c3d";
        for (int round = 0; round < 2; round++) { // the first is the warm-up
            MessageCodes.Check check = codes.check();
            long[] make = new long[n];
            long[] verify = new long[n];
            long base = EpochClock.nowNanos();
            for (int i = 0; i < n; i++) {
                String seq = Long.toString(base + i);
                String time = Long.toString(base);
                long t0 = System.nanoTime();
                String mac = codes.code(subject, sender, seq, time, null, null, data);
                long t1 = System.nanoTime();
                if (check.check(subject, sender, seq, time, null, null, data, mac, base) != null) {
                    throw new IllegalStateException("a valid message was dropped");
                }
                long t2 = System.nanoTime();
                make[i] = t1 - t0;
                verify[i] = t2 - t1;
            }
            if (round == 1) {
                System.out.println("make a code:  " + summary(make));
                System.out.println("check a code: " + summary(verify));
            }
        }
    }

    private static String summary(long[] nanos) {
        long[] sorted = nanos.clone();
        Arrays.sort(sorted);
        return "count " + sorted.length + ", p50 " + sorted[sorted.length / 2] + " ns, p99 "
                + sorted[(int) (sorted.length * 0.99)] + " ns, max " + sorted[sorted.length - 1] + " ns";
    }
}
