package io.dtron.model.delta;

import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import io.dtron.model.internal.DeltaWidener;
import io.dtron.xta.ModelSyntax;
import java.util.List;
import java.util.Map;

/**
 * The Delta-extended model of a distributed test (DTRON thesis, section 3.5, step 2): the model with the clock
 * bounds of its observable edges widened by the delays that inputs and outputs take between the tester and the
 * system under test, so that it can be verified again with those delays taken into account.
 *
 * <p>On each edge that synchronises on an input or output channel of the test interface, a lower clock bound of
 * the guard ({@code x >= lb}, {@code x > lb}) becomes {@code lb + low_in + low_out} and an upper bound of the
 * guard or of the source location's invariant ({@code x <= ub}, {@code x < ub}) becomes
 * {@code ub + high_in + high_out}; {@code x == c} in a guard becomes both. The edge's own channel gives the
 * interval of its direction, the hull of the other direction's channels the other one (0 when none is given).
 * Delays are microseconds; the sums are turned into model time units rounding outward (lower bounds down, upper
 * bounds up). The bound text is kept and the widening added to it ({@code x >= (P - T) + 3}), in place: the rest
 * of the file stays as it was, byte for byte, but for a comment at the top of the global declarations that says
 * what was widened. Clock differences, bounds that are not constant and anything else that is no clock-versus-
 * constant bound are left as they are and listed in {@link Result#left()}.
 */
public final class DeltaExtension {

    private DeltaExtension() {
    }

    /**
     * The delays of one channel, from the sender's publication to the receiver's use: for an input, from the
     * tester's publication to the adapter's application; for an output, from the system's event to the
     * tester's receipt.
     *
     * @param lowMicros  the shortest delay, in microseconds, at least 0
     * @param highMicros the longest delay, in microseconds, at least {@code lowMicros}
     */
    public record Delay(long lowMicros, long highMicros) {
        public Delay {
            if (lowMicros < 0 || highMicros < lowMicros) {
                throw new IllegalArgumentException("a delay interval needs 0 <= low <= high, not " + lowMicros + ".."
                        + highMicros + " us");
            }
        }

        /** The smallest interval that holds both. */
        public Delay hull(Delay other) {
            return new Delay(Math.min(lowMicros, other.lowMicros), Math.max(highMicros, other.highMicros));
        }
    }

    /**
     * A widened bound.
     *
     * @param place  where it is: the line, the template, the edge or location and the label
     * @param before the comparison as it was written
     * @param after  the comparison as it is now written
     */
    public record Change(String place, String before, String after) {
    }

    /**
     * A clock comparison of an observable edge (or of its source location's invariant) that was left as it was.
     *
     * @param place  where it is, as in {@link Change#place()}
     * @param text   the comparison
     * @param reason why it was left
     */
    public record Left(String place, String text, String reason) {
    }

    /**
     * The Delta-extended model.
     *
     * @param text     the model's text with the widened bounds and the comment saying what was widened
     * @param changes  the widened bounds, in the order of the file
     * @param left     the clock comparisons of observable edges that were left, in the order of the file
     * @param warnings what the caller should know: a label that several processes share, widened for all of them
     *                 though not all of them use it on an observable edge
     */
    public record Result(String text, List<Change> changes, List<Left> left, List<String> warnings) {
        public Result {
            changes = List.copyOf(changes);
            left = List.copyOf(left);
            warnings = List.copyOf(warnings);
        }
    }

    /**
     * Widens the bounds of {@code network}'s observable edges in {@code text}.
     *
     * @param network        the model, loaded from {@code text} (its positions point into it)
     * @param text           the model's text as decoded for loading ({@code ModelSyntax.decode}), XML or XTA
     * @param testInterface  the model's inputs and outputs
     * @param delays         the delay intervals, by channel name on the bus ({@code move} for {@code i_move});
     *                       at least one
     * @param timeUnitMicros microseconds per model time unit
     * @param source         where the delays come from, for the comment ({@code "--delta move=200..1500"})
     * @return the extended model and what was widened
     * @throws IllegalArgumentException when a delay names no channel of the interface, no delay is given, the
     *                                  time unit is not positive, a widened bound would not fit in 32 bits, or the
     *                                  network or interface was not loaded from this text
     */
    public static Result extend(Network network, String text, TestInterface testInterface, Map<String, Delay> delays,
                                long timeUnitMicros, String source) {
        return new DeltaWidener(network, text, testInterface, delays, timeUnitMicros, source).widen();
    }

    /**
     * {@code text} encoded as the model file {@code original} was ({@link ModelSyntax#encodingOf}: UTF-16 stays
     * UTF-16 in its byte order, else the charset the XML declaration names, else UTF-8), with the same byte-order
     * mark when it had one.
     */
    public static byte[] encodeLike(String text, byte[] original) {
        int bom = ModelSyntax.byteOrderMark(original);
        byte[] body = text.getBytes(ModelSyntax.encodingOf(original));
        byte[] out = new byte[bom + body.length];
        System.arraycopy(original, 0, out, 0, bom);
        System.arraycopy(body, 0, out, bom, body.length);
        return out;
    }
}
