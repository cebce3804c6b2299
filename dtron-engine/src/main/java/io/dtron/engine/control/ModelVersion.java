package io.dtron.engine.control;

import io.dtron.engine.UnsupportedModelException;
import io.dtron.engine.verify.Query;
import io.dtron.engine.verify.QueryException;
import io.dtron.engine.verify.VerificationResult;
import io.dtron.engine.verify.Verifier;
import io.dtron.engine.verify.VerifierOptions;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.util.List;
import java.util.Objects;

/**
 * A version of the controller's model, checked before a run takes it ({@link Controller#offer}): it loads (the
 * caller loaded it), has the running version's commands and readings with their variables, and every one of its
 * queries holds, as {@code dtron verify} checks them.
 *
 * @param label         what the version is called in messages (its file name)
 * @param network       the model
 * @param testInterface its commands ({@code i_}) and readings ({@code o_})
 */
public record ModelVersion(String label, Network network, TestInterface testInterface) {
    public ModelVersion {
        Objects.requireNonNull(label, "label");
        Objects.requireNonNull(network, "network");
        Objects.requireNonNull(testInterface, "testInterface");
    }

    /**
     * The outcome of a {@link #check}: the version, and why it is refused (null when it is accepted).
     *
     * @param version the version checked
     * @param refusal why it is refused, or null
     */
    public record Check(ModelVersion version, String refusal) {
        /** Whether the version may be taken. */
        public boolean accepted() {
            return refusal == null;
        }
    }

    /**
     * Checks {@code candidate} against the version the run has ({@code running}'s interface) and {@code queries}
     * (none is a refusal: a version must say what it guarantees): the same commands and readings with the same
     * variables, and every query satisfied (one violated, undecided, skipped or in error refuses the version).
     */
    public static Check check(ModelVersion candidate, TestInterface running, List<Query> queries) {
        String differs = interfaceDiffers(running, candidate.testInterface());
        if (differs != null) {
            return new Check(candidate, differs);
        }
        if (queries.isEmpty()) {
            return new Check(candidate, "it has no queries (a .q file beside it, or in the model) to check it with");
        }
        Verifier verifier;
        try {
            verifier = new Verifier(candidate.network(), VerifierOptions.defaults());
        } catch (UnsupportedModelException e) {
            return new Check(candidate, "DTRON's engine cannot run it: " + e.getMessage());
        }
        for (int i = 0; i < queries.size(); i++) {
            Query q = queries.get(i);
            String which = "query [" + (i + 1) + "] " + q.text();
            VerificationResult r;
            try {
                r = verifier.verify(q);
            } catch (QueryException | UnsupportedModelException e) {
                return new Check(candidate, which + ": " + e.getMessage());
            }
            switch (r.outcome()) {
                case SATISFIED -> {
                }
                case VIOLATED -> {
                    return new Check(candidate, which + " is NOT satisfied");
                }
                default -> {
                    return new Check(candidate, which + " is " + r.outcome().name().toLowerCase(java.util.Locale.ROOT)
                            + (r.reason() == null ? "" : ": " + r.reason()));
                }
            }
        }
        return new Check(candidate, null);
    }

    /** How the commands and readings of {@code candidate} differ from {@code running}'s, or null when they do not. */
    private static String interfaceDiffers(TestInterface running, TestInterface candidate) {
        String inputs = differ("commands", running.inputs(), candidate.inputs());
        return inputs != null ? inputs : differ("readings", running.outputs(), candidate.outputs());
    }

    private static String differ(String what, List<TestInterface.ObservableChannel> running,
                                 List<TestInterface.ObservableChannel> candidate) {
        List<String> a = running.stream().map(ModelVersion::signature).sorted().toList();
        List<String> b = candidate.stream().map(ModelVersion::signature).sorted().toList();
        return a.equals(b) ? null : "its " + what + " " + b + " are not the running version's " + a;
    }

    private static String signature(TestInterface.ObservableChannel c) {
        return c.name() + (c.variables().isEmpty() ? "" : c.variables().stream()
                .map(TestInterface.AttachedVariable::name).toList().toString());
    }
}
