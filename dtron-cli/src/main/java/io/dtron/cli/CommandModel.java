package io.dtron.cli;

import io.dtron.model.ModelException;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.io.PrintWriter;
import java.nio.file.Path;

/**
 * The model a command works on, loaded as every command loads it: the network from MODEL (.xml, .xta, .ta), its
 * interface from {@code --interface FILE.trn} or else from the {@code i_}/{@code o_} names. A model that does not
 * load prints its errors ({@link CheckCommand#printErrors}), and one too large for the JVM's memory says so in one
 * line; the command then exits with 1.
 */
final class CommandModel {
    private CommandModel() {
    }

    /**
     * A loaded model with its interface.
     *
     * @param network       the model
     * @param testInterface its interface
     */
    record Loaded(Network network, TestInterface testInterface) {
    }

    /**
     * The interface of {@code network}: from {@code interfaceFile} (.trn) when given, else from the channel names.
     *
     * @throws ModelException if the file does not parse or names what the model does not have, or the names do not
     *                        make an interface
     */
    static TestInterface interfaceOf(Network network, Path interfaceFile) throws ModelException {
        return interfaceFile == null ? TestInterface.fromNames(network)
                : TestInterface.fromFile(network, interfaceFile);
    }

    /**
     * Loads the network of {@code dtron command}; prints why not and returns null when it does not load.
     */
    static Network network(String command, Path model, PrintWriter err) {
        try {
            return ModelLoader.load(model);
        } catch (ModelException e) {
            CheckCommand.printErrors(model, e, err);
        } catch (OutOfMemoryError e) {
            err.println("dtron " + command + ": " + JvmLimits.modelTooLarge(command, model));
        }
        return null;
    }

    /**
     * Loads the network of {@code dtron command} and its interface; prints why not and returns null when either
     * does not load.
     */
    static Loaded load(String command, Path model, Path interfaceFile, PrintWriter err) {
        Network network = network(command, model, err);
        if (network == null) {
            return null;
        }
        try {
            return new Loaded(network, interfaceOf(network, interfaceFile));
        } catch (ModelException e) {
            CheckCommand.printErrors(model, e, err);
            return null;
        }
    }
}
