package io.dtron.models.streetlight;

import java.io.IOException;
import java.io.InputStream;
import java.io.UncheckedIOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;

/**
 * The street-light model, {@code io/dtron/models/streetlight/streetlight.xml}: operators log in, open the list
 * of controllers, tick one of their two controllers, switch it to a state, check the result and log out, again
 * and again, each answered by {@code o_result(user, resCode)}. The model declares {@code const int USERS = 2;}
 * {@link #write} makes a copy for another number of operators. One time unit is {@value #TIME_UNIT_MICROS} us.
 */
public final class StreetLightModel {
    /** The model as a class-path resource. */
    public static final String RESOURCE = "/io/dtron/models/streetlight/streetlight.xml";
    /** Microseconds per model time unit: 100 ms, so that browser steps fit the model's windows. */
    public static final long TIME_UNIT_MICROS = 100_000;
    /** The most operators: controllers are numbered in two decimal digits of the result codes. */
    public static final int MAX_USERS = 50;

    private static final String USERS_DECLARATION = "const int USERS = 2;";

    private StreetLightModel() {
    }

    /** Returns the model's text for {@code users} operators. */
    public static String text(int users) {
        if (users < 1 || users > MAX_USERS) {
            throw new IllegalArgumentException("the model has 1 to " + MAX_USERS + " operators, not " + users);
        }
        String text;
        try (InputStream in = StreetLightModel.class.getResourceAsStream(RESOURCE)) {
            if (in == null) {
                throw new IllegalStateException("the class path has no " + RESOURCE);
            }
            text = new String(in.readAllBytes(), StandardCharsets.UTF_8);
        } catch (IOException e) {
            throw new UncheckedIOException("cannot read " + RESOURCE, e);
        }
        if (!text.contains(USERS_DECLARATION)) {
            throw new IllegalStateException(RESOURCE + " no longer declares '" + USERS_DECLARATION + "'");
        }
        return text.replace(USERS_DECLARATION, "const int USERS = " + users + ";");
    }

    /**
     * Writes the model for {@code users} operators to {@code streetlight-USERS.xml} in a folder.
     *
     * @return the file
     */
    public static Path write(Path folder, int users) throws IOException {
        Path file = folder.resolve("streetlight-" + users + ".xml");
        Files.writeString(file, text(users), StandardCharsets.UTF_8);
        return file;
    }
}
